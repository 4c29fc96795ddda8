#pragma once
// The two circular paths of the accuracy report, computed on the machine's error model: an
// X-Y circle around mid-travel with the rotary axes at zero (what a ballbar records of the
// geometric errors alone), and a TCP circle with the tool tilted towards its centre (a
// cone-frustum-like 5-axis path through the generic inverse kinematics).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// The options of `report` (built by the Python package, python/mtacc/report.py): where it goes,
// the machine's set-up, and the measured files and models each adding a section. The values
// are checked where each section reads them.
const OptionSchema& reportSchema();

struct CirclePathResult {
  std::shared_ptr<const Machine> machine;
  std::string description;
  double radius = 0;            // mm
  Vec3 centre = Vec3::Zero();   // workpiece frame, mm
  std::vector<double> phi;      // rad
  JointMatrix q;                // mm, rad
  PointMatrix radialDirection;  // unit, workpiece frame
  std::vector<double> radialDeviation;  // mm
};

// Both return nullopt where the machine has no such path (no X and Y axes; not two rotary
// axes); the tilted circle throws UnreachablePose when the path cannot be solved.
std::optional<CirclePathResult> xyCircleTest(const MachineSetup& setup, int points = 361);
std::optional<CirclePathResult> tiltedCircleTest(const MachineSetup& setup, int points = 181);
nlohmann::json toJson(const CirclePathResult& result);

}  // namespace mtacc
