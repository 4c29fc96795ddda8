#pragma once
// Workflow `stiffness`: the finite-stiffness changes of a machine's errors (seed 003 §4.2,
// §5.4) at the load of its state, and what they do to the TCP over the working volume, beside
// what the geometric errors alone do (the comparison of seed 003 §5.4).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// The largest TCP position error over the grid (mm) and the pose where it occurs.
struct LargestTcpError {
  double value = 0.0;
  std::vector<double> pose;
};

struct StiffnessSummary {
  MachineSetup setup;
  int samplesPerAxis = 0;
  int poses = 0;
  LargestTcpError geometric;  // the errors without the stiffness changes
  LargestTcpError stiffness;  // the stiffness changes alone
  LargestTcpError change;     // all the errors minus the geometric ones: what the load and the other axes add
};

// The options of `stiffness`, declared once (samples: positions per axis of the grid), and the
// samples they give.
const OptionSchema& stiffnessSchema();
int stiffnessSamples(const OptionValues& values);

// Over workingVolumeGrid(samplesPerAxis), samplesPerAxis within the schema's range; throws
// InputError when the errors have no stiffness changes.
StiffnessSummary summariseStiffness(const MachineSetup& setup, int samplesPerAxis = 5);
// The errors without their stiffness changes, and the stiffness changes alone.
ErrorModel withoutStiffness(const ErrorModel& errors);
ErrorModel stiffnessOnly(const Machine& machine, const ErrorModel& errors);

// Each change with its values and its largest magnitude at the state's load (um or urad;
// positions in mm or deg), and the three largest TCP errors in um.
nlohmann::json toJson(const StiffnessSummary& summary);

}  // namespace mtacc
