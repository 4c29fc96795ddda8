#pragma once
// Sensitivities and the error budget: how much each error parameter moves the TCP.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

// One error parameter set to epsilon (mm or rad), the others zero.
struct ErrorStep {
  Parameter parameter;
  double epsilon = 0.0;
};
// A pose q and the outward surface normal there (positive = material left standing).
struct SurfacePoint {
  const double* q = nullptr;
  Vec3 normal = Vec3::UnitZ();
};
// Seed 001 eq. 15: k = E / epsilon, where E is the TCP deviation along the normal caused by
// the single error, computed with the exact model (`shape` gives the error functions' shapes).
double sensitivityCoefficient(std::shared_ptr<const Machine> machine, const ErrorModel& shape, const ErrorStep& step,
                              const SurfacePoint& at);

// One budget line: a single error at a stated magnitude.
struct BudgetItem {
  std::string name;
  Dimension dimension;
  double magnitude;   // mm or rad
  ErrorModel errors;  // the machine with only this error
};

struct BudgetEntry {
  std::string name;
  Dimension dimension;
  double magnitude;
  double maxPositionError;     // largest |TCP deviation| over the sampled volume, mm
  double maxOrientationError;  // largest |tool orientation error|, rad
  std::vector<double> worstPose;
};

// Every location error at `length` / `angle`, and each of the six component errors of every
// axis as a constant of that magnitude.
std::vector<BudgetItem> budgetItemsAtMagnitude(const Machine& machine, double length, double angle);
// Each non-zero location error of `errors`, alone, at its own value, and each non-zero
// component error function whole (all its terms), named by the function ("EXX") with its
// largest |value| over the axis's travel as the magnitude.
std::vector<BudgetItem> budgetItemsOfModel(const Machine& machine, const ErrorModel& errors);

// Grid of `samplesPerAxis` positions per commanded axis over its travel (one turn for a
// continuous rotary axis): samplesPerAxis^axes poses.
JointMatrix workingVolumeGrid(const Machine& machine, int samplesPerAxis);

// Sorted by maxPositionError, largest first. progress(done, total) is called per item.
std::vector<BudgetEntry> errorBudget(std::shared_ptr<const Machine> machine, const std::vector<BudgetItem>& items,
                                     const JointMatrix& poses, int threads = kAllCores,
                                     const std::function<void(size_t, size_t)>& progress = {});

}  // namespace mtacc
