#pragma once
// Workflows `budget` and `sensitivity`: how much each error moves the TCP, over the working
// volume and at one pose.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/kinematics/budget.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct BudgetOptions {
  int samplesPerAxis = 5;  // 2 .. 50 positions per axis across its travel
  // Every error at these magnitudes (mm, rad); when both are empty and the machine has
  // errors, each of its non-zero errors alone at its own value.
  std::optional<double> length, angle;
  int threads = kAllCores;
  std::function<void(size_t, size_t)> progress;
};

struct BudgetResult {
  std::shared_ptr<const Machine> machine;
  bool atMagnitude = false;
  double length = 0, angle = 0;  // the magnitudes, when atMagnitude
  int samplesPerAxis = 0;
  JointMatrix grid;
  std::vector<BudgetEntry> entries;  // largest first
  double combinedMaxPositionError = 0;  // all errors of the description together, mm
};

// The options of `budget`, declared once (core/option_schema.hpp), and the options they describe.
const OptionSchema& budgetSchema();
BudgetOptions budgetOptions(const OptionValues& values);

BudgetResult errorBudget(const MachineSetup& setup, const BudgetOptions& options = {});
// The poses the budget evaluates: `samples` per axis (the schema's range) over each travel.
JointMatrix workingVolumeGrid(const MachineSetup& setup, int samples);
nlohmann::json toJson(const BudgetResult& result);
std::string basisText(const BudgetResult& result);

struct SensitivityRequest {
  std::vector<double> q;               // mm, rad
  std::optional<Vec3> direction;       // of E; default: the tool direction
  std::vector<std::string> parameters; // default: every parameter
  double epsilonLength = 0.01;         // mm, for k = E / epsilon
  double epsilonAngle = 30e-6;         // rad
};

struct SensitivityRow {
  Parameter parameter;
  Vec3 position;        // um per unit of the parameter (um or urad)
  Vec3 orientation;     // urad per unit
  double kFirstOrder;   // um per unit, along the direction
  double kExact;
};

struct SensitivityResult {
  std::shared_ptr<const Machine> machine;
  std::vector<double> q;
  Vec3 direction;  // unit
  std::vector<SensitivityRow> rows;
};

SensitivityResult sensitivities(const MachineSetup& setup, const SensitivityRequest& request);
// pose (required), direction, parameters, epsilon_length, epsilon_angle; the pose read against
// the machine of `setup`.
const OptionSchema& sensitivitySchema();
SensitivityRequest sensitivityRequest(const MachineSetup& setup, const OptionValues& values);

// k = E / epsilon of the error `name` alone at exactly `epsilon` (mm or rad, not zero) at pose `q`
// (mm, rad; within travel), along `direction` (seed 001 eq. 15).
double sensitivityCoefficientAt(const MachineSetup& setup, const std::vector<double>& q, const std::string& name, double epsilon,
                                const Vec3& direction);
nlohmann::json toJson(const SensitivityResult& result);

}  // namespace mtacc
