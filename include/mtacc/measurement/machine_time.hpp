#pragma once
// How long a measurement takes out of production: each run's motion (the axes' rapid feeds and
// accelerations between static readings, the run's feed along a contouring path), a dwell per
// static reading, and the set-ups (a sphere placed once for the runs that use it where it is, a
// ballbar mounted per run, an instrument mounted once). Minutes.
#include <string>
#include <vector>

#include "mtacc/core/units.hpp"
#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

struct MachineTimeModel {
  double linearRapid = 10000.0;      // mm/min
  double rotaryRapid = 3600.0 * kDeg;  // rad/min (10 rpm)
  double linearAcceleration = 1000.0;  // mm/s^2
  double rotaryAcceleration = 180.0 * kDeg;  // rad/s^2
  double rtestDwell = 2.0;           // s per R-test position (settling and reading)
  double probeTime = 20.0;           // s per probed sphere (five touches)
  double setupMinutes = 3.0;         // a sphere placed, a ballbar mounted: per set-up
  double instrumentMinutes = 15.0;   // an instrument mounted and its readings checked: once
};

// The time of the run's motion and readings, minutes (no set-up): static readings (R-test,
// probe) positioned at rapid with a trapezoidal profile per axis, the slowest axis setting each
// move; contouring runs (ballbar, directional) at the run's feed along the linear axes' path, no
// faster than the rapid of any axis.
double runMinutes(const Machine& machine, const MeasurementRun& run, const MachineTimeModel& time);

// The set-up a run needs: its instrument and where its sphere sits on the workpiece with which
// tool ball (an R-test or a probe: runs that share it share the set-up, whatever the axes do); a
// ballbar is mounted for each run.
std::string setupKey(const MeasurementRun& run);

// A plan's time, minutes: its runs, each set-up once (setupMinutes) and each instrument once
// (instrumentMinutes).
double planMinutes(const Machine& machine, const std::vector<MeasurementRun>& runs, const MachineTimeModel& time);

}  // namespace mtacc
