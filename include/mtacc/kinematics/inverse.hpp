#pragma once
// Inverse kinematics of the nominal machine, for any topology with 0, 1 or 2 rotary axes
// (any directions, inclined axes included): TCP position and tool direction in the
// workpiece frame -> commanded axis positions. All solutions are returned; the branch
// choice is documented in docs/conventions.md ("Inverse kinematics").
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

enum class TiltBranch {
  Auto,      // closest to the hint (or to the reference pose when there is no hint)
  Positive,  // tilt axis (the rotary axis nearer the tool in the chain) >= 0
  Negative,  // tilt axis <= 0
};

// "auto", "positive" or "negative"; throws InputError otherwise.
TiltBranch parseTiltBranch(const std::string& name);

struct IkOptions {
  TiltBranch branch = TiltBranch::Auto;
  // Previous pose along a path: rotary angles are chosen closest to it (unwrapping
  // continuous axes), and a free angle at a singular pose keeps the hint's value.
  std::optional<std::vector<double>> hint;
  double singularTolerance = 1e-9;  // |sin| of the angle that decides a singularity
};

struct IkSolution {
  std::vector<double> q;     // commanded axes, mm and rad
  bool withinTravel = true;
  std::string travelViolation;  // e.g. "B=130 deg beyond travel [-120, 120] deg"
  bool singular = false;        // a rotary angle was free (tool along an axis)
  std::string singularAxis;
};

struct IkResult {
  std::vector<IkSolution> solutions;  // preferred first; solutions beyond travel last
};

// Every solution (with rotary equivalents within +-2 turns inside travel). Throws
// UnreachablePose if the direction cannot be reached or the position cannot be solved.
IkResult inverseKinematics(const KinematicModel& nominal, const Vec3& position, const Vec3& toolDirection,
                           const IkOptions& options = {});

// The preferred solution within travel; throws UnreachablePose naming the pose otherwise.
IkSolution solveIk(const KinematicModel& nominal, const Vec3& position, const Vec3& toolDirection,
                   const IkOptions& options = {});

// A target of a path that cannot be reached; `index` counts from 0 along the path.
class UnreachableTarget : public UnreachablePose {
 public:
  UnreachableTarget(size_t index, const std::string& what) : UnreachablePose(what), index(index) {}
  size_t index;
};

// A path: each pose solved with the previous solution as hint (continuity, unwrapping).
// The first pose uses options.branch. Throws UnreachableTarget.
std::vector<IkSolution> solveIkPath(const KinematicModel& nominal, const std::vector<Vec3>& positions,
                                    const std::vector<Vec3>& directions, const IkOptions& options = {});

}  // namespace mtacc
