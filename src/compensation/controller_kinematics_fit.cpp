#include "controller_kinematics_fit.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc::controller_fit {
namespace {

// An error alone is carried when the fit leaves less of it than this (mm), or than this share of its
// effect: the parameters carry errors exactly up to second-order terms of micrometres over hundreds of mm.
constexpr double kCarriedLeft = 1e-6, kCarriedShare = 1e-3;
// The values are lengths (mm) and angles or direction components (rad). A combination of them
// that moves the tool tip by less than this RMS over the poses per unit (0.1 mm per mm or per rad:
// an angle about a line less than 0.1 mm from the poses' centre of turning, a point's position
// along its own axis line, rounding) is one the poses cannot tell apart from doing nothing, or
// only through lever arms of the errors' own micrometres: the solution leaves it alone (least norm).
constexpr double kSeenPerUnit = 0.1;

// The least-norm step for the residual r over the well-determined directions of the columns.
class Solver {
 public:
  explicit Solver(const Eigen::MatrixXd& j) : svd_(j, Eigen::ComputeThinU | Eigen::ComputeThinV) {
    const double seen = kSeenPerUnit * std::sqrt(static_cast<double>(j.rows()) / 3.0);
    const auto& sigma = svd_.singularValues();
    while (rank_ < sigma.size() && sigma[rank_] > seen) ++rank_;
  }
  Eigen::VectorXd step(const Eigen::VectorXd& r) const {
    const auto u = svd_.matrixU().leftCols(rank_);
    const Eigen::VectorXd along = (u.transpose() * r).cwiseQuotient(svd_.singularValues().head(rank_));
    return svd_.matrixV().leftCols(rank_) * along;
  }
  // r less its part the columns can make.
  Eigen::VectorXd rest(const Eigen::VectorXd& r) const {
    const auto u = svd_.matrixU().leftCols(rank_);
    return r - u * (u.transpose() * r);
  }

 private:
  Eigen::JacobiSVD<Eigen::MatrixXd> svd_;
  Eigen::Index rank_ = 0;
};

std::vector<double> spread(double low, double high, int count, bool closed) {
  std::vector<double> v(static_cast<size_t>(count));
  const double step = (high - low) / (closed ? count - 1 : count);
  for (int k = 0; k < count; ++k) v[static_cast<size_t>(k)] = low + k * step;
  return v;
}

Eigen::MatrixXd jacobian(const KinematicModel& machine, const Model& model, const std::vector<ControllerPose>& poses) {
  constexpr double h = 1e-3;  // mm, or 1e-3 of a unit vector's component, or mrad
  Eigen::MatrixXd j(3 * static_cast<Eigen::Index>(poses.size()), static_cast<Eigen::Index>(model.values.size()));
  for (size_t k = 0; k < model.values.size(); ++k) {
    double& value = *model.values[k];
    const double kept = value;
    value = kept + h;
    const Eigen::VectorXd plus = residual(machine, model, poses);
    value = kept - h;
    j.col(static_cast<Eigen::Index>(k)) = (plus - residual(machine, model, poses)) / (2.0 * h);
    value = kept;
  }
  return j;
}

}  // namespace

std::vector<ControllerPose> poseLattice(const Machine& m, const std::array<size_t, 3>& linear, size_t first, size_t second) {
  const double halfTurn = std::numbers::pi;
  const auto& firstTravel = m.axes[first].travel;
  const auto& secondTravel = m.axes[second].travel;
  const std::vector<double> firsts =
      firstTravel ? spread(firstTravel->min, firstTravel->max, 9, true) : spread(-halfTurn / 2, halfTurn / 2, 9, true);
  const std::vector<double> seconds =
      secondTravel ? spread(secondTravel->min, secondTravel->max, 12, true) : spread(0.0, 2.0 * halfTurn, 12, false);
  std::array<std::vector<double>, 3> lattice;
  for (size_t k = 0; k < 3; ++k) {
    const auto& travel = m.axes[linear[k]].travel;
    if (!travel) throw InputError({m.sourceFile, 0, m.axes[linear[k]].name}, "the fit of a controller's kinematics needs the axis's travel");
    const double middle = 0.5 * (travel->min + travel->max), quarter = 0.25 * (travel->max - travel->min);
    lattice[k] = {middle - quarter, middle, middle + quarter};
  }
  std::vector<ControllerPose> poses;
  for (double a : firsts)
    for (double b : seconds)
      for (double x : lattice[0])
        for (double y : lattice[1])
          for (double z : lattice[2]) poses.push_back({{x, y, z}, a, b});
  return poses;
}

void keepWithinTravel(const Machine& m, std::vector<ControllerPose>& poses,
                      const std::function<std::vector<double>(const ControllerPose&)>& commands) {
  std::erase_if(poses, [&](const ControllerPose& pose) {
    const std::vector<double> q = commands(pose);
    for (size_t k = 0; k < q.size(); ++k) {
      const auto& travel = m.axes[k].travel;
      if (travel && (q[k] < travel->min - 1e-9 || q[k] > travel->max + 1e-9)) return true;
    }
    return false;
  });
  if (poses.size() < 10) throw InputError({m.sourceFile, 0, "axes"}, "fewer than 10 poses of the fit lie within travel");
}

Mat3 turned(const Vec3& turn) {
  const double angle = turn.norm();
  return angle > 0.0 ? Mat3(Eigen::AngleAxisd(angle, turn / angle)) : Mat3::Identity();
}

Eigen::VectorXd residual(const KinematicModel& machine, const Model& model, const std::vector<ControllerPose>& poses) {
  Eigen::VectorXd r(3 * static_cast<Eigen::Index>(poses.size()));
  const Mat3 frame = model.turn ? turned(*model.turn) : Mat3::Identity();
  for (size_t k = 0; k < poses.size(); ++k) {
    const std::vector<double> q = model.commands(poses[k]);
    r.segment<3>(3 * static_cast<Eigen::Index>(k)) = toolPosition(machine, q.data()) - model.origin - frame * poses[k].world;
  }
  return r;
}

void fit(const KinematicModel& machine, const Model& model, const std::vector<ControllerPose>& poses) {
  Eigen::VectorXd r = residual(machine, model, poses);
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::VectorXd step = Solver(jacobian(machine, model, poses)).step(-r);
    for (size_t k = 0; k < model.values.size(); ++k) *model.values[k] += step[static_cast<Eigen::Index>(k)];
    const Eigen::VectorXd next = residual(machine, model, poses);
    // Converged when a step no longer lowers the residual by a millionth; a step that raises it is taken back.
    if (next.norm() >= (1.0 - 1e-6) * r.norm()) {
      if (next.norm() > r.norm())
        for (size_t k = 0; k < model.values.size(); ++k) *model.values[k] -= step[static_cast<Eigen::Index>(k)];
      break;
    }
    r = next;
  }
}

double largestPerPose(const Eigen::VectorXd& r) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k < r.size(); k += 3) largest = std::max(largest, r.segment<3>(k).norm());
  return largest;
}

TableResidual residualFigures(const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  TableResidual r;
  r.samples = static_cast<int>(before.size() / 3);
  r.beforeMax = largestPerPose(before);
  r.afterMax = largestPerPose(after);
  r.beforeRms = std::sqrt(before.squaredNorm() / r.samples);
  r.afterRms = std::sqrt(after.squaredNorm() / r.samples);
  return r;
}

std::vector<std::string> notCarried(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const Model& model,
                                    const std::vector<ControllerPose>& poses) {
  const Machine& m = *machine;
  const KinematicModel nominal = compileNominal(machine);
  const Eigen::VectorXd base = residual(nominal, model, poses);
  const Solver carried(jacobian(nominal, model, poses));
  std::vector<std::string> left;
  for (const Parameter& p : nonZeroParameters(m, errors)) {
    const ErrorModel alone = singleError(m, errors, p, parameterValue(errors, p));
    const Eigen::VectorXd effect = residual(compile(machine, alone), model, poses) - base;
    const double largest = largestPerPose(effect), rest = largestPerPose(carried.rest(effect));
    if (rest > std::max(kCarriedLeft, kCarriedShare * largest))
      left.push_back(fmt::format("{} (leaves {:.3f} um; {:.3f} um uncorrected)", p.name, rest * 1e3, largest * 1e3));
  }
  if (const auto reversal = reversalFunctions(m, errors); !reversal.empty())
    left.push_back(fmt::format("the reversal terms of {} (the kinematics have no direction of motion)", fmt::join(reversal, ", ")));
  if (!errors.stiffness.empty())
    left.push_back(fmt::format("{} changes of component errors with another axis or the load (the kinematics are rigid)", errors.stiffness.size()));
  return left;
}

}  // namespace mtacc::controller_fit
