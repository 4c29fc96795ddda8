#pragma once
// Spindle drift tests (docs/file-formats.md "Drift tests", ISO 230-3, seed 003 §2.6): the
// probes' readings of a test mandrel, the spindle speed and any number of temperatures.
//   # probe_z: 50, 150 mm               machine z of probe sets 1 and 2 (needed for the tilts)
//   # sensor: head, spindle head front  a temperature channel's location (free text; optional)
//   time_s,x1_um,y1_um,x2_um,y2_um,z_um,spindle_rpm,Z_mm,head_C,column_C
// (Z_mm: where an axis stood at each reading, for a drift that depends on the position.)
#include <Eigen/Dense>

#include <optional>
#include <string>
#include <vector>

#include "mtacc/thermal/drift_test.hpp"

namespace mtacc {

struct DriftTestFile {
  std::string file;
  int headerLine = 1;
  Eigen::VectorXd time;                          // s, increasing
  MandrelProbes probes;                          // mm
  std::optional<Eigen::VectorXd> spindleSpeed;   // rpm
  std::vector<std::string> axes;                 // axis position channels, named without "_mm"
  Eigen::MatrixXd positions;                     // samples x axes, mm
  std::vector<std::string> sensors;              // temperature channels, named without "_C"
  std::vector<std::string> sensorLocations;      // per sensor; empty when not given
  Eigen::MatrixXd temperatures;                  // samples x sensors, degC
};

// Throws InputError naming file, line and column or key: an unknown or missing column (time_s
// and at least one probe), time that does not increase, a probe reading beyond +-10 mm, a
// temperature outside -50 .. 150 degC, a speed outside 0 .. 200,000 rpm, an axis position beyond
// +-100 m, fewer than 3 samples,
// probe_z missing or equal where a tilt needs it, a sensor key naming no column.
DriftTestFile readDriftTestCsv(const std::string& path);
DriftTestFile parseDriftTestCsv(const std::string& text, const std::string& sourceName);

// The file's text, `note` as its first line; readings to 1 nm, temperatures to 1 mK.
std::string driftTestCsv(const DriftTestFile& test, const std::string& note);

}  // namespace mtacc
