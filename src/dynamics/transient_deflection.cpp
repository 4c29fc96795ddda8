#include "mtacc/dynamics/transient_deflection.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"

namespace mtacc {

std::vector<Vec3> accelerationDeflection(const StructureModel& model, const std::vector<double>& positions,
                                         const std::vector<std::vector<double>>& accelerations, double period) {
  if (!(period > 0.0) || !std::isfinite(period)) throw InvalidInput("deflection: the period must be positive and finite");
  if (accelerations.size() != model.axes.size()) throw InvalidInput("deflection: one acceleration series per structure axis");
  size_t samples = 0;
  for (const auto& series : accelerations)
    if (!series.empty()) {
      if (samples != 0 && series.size() != samples) throw InvalidInput("deflection: acceleration series of different lengths");
      samples = series.size();
    }
  std::vector<Vec3> out(samples, Vec3::Zero());
  if (samples == 0) return out;

  const auto matrices = assembleStructure(model, positions);
  const auto modes = undampedModes(model, matrices);
  const Eigen::VectorXd damping = modalDampingCoefficients(matrices, modes);
  const Eigen::MatrixXd modalLoads = modes.shapes.transpose() * matrices.inertialLoads;          // modes x axes
  const Eigen::Matrix<double, 3, Eigen::Dynamic> participation = matrices.selection * modes.shapes;  // S phi_r
  Eigen::MatrixXd load = Eigen::MatrixXd::Zero(modes.shapes.cols(), static_cast<Eigen::Index>(samples));  // phi_r^T f(t_k)
  for (size_t j = 0; j < accelerations.size(); ++j)
    for (size_t k = 0; k < accelerations[j].size(); ++k) load.col(static_cast<Eigen::Index>(k)) += modalLoads.col(static_cast<Eigen::Index>(j)) * accelerations[j][k];

  for (Eigen::Index r = 0; r < modes.shapes.cols(); ++r) {
    const double w = 2 * kPi * modes.frequencies[r];
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -w * w, -damping[r];
    const Eigen::Matrix2d step = (a * period).exp();
    const Eigen::Vector2d input = a.inverse() * (step - Eigen::Matrix2d::Identity()) * Eigen::Vector2d(0.0, 1.0);  // per unit load held
    Eigen::Vector2d state = Eigen::Vector2d::Zero();
    const Vec3 c = participation.col(r);
    for (size_t k = 1; k < samples; ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      state = step * state + input * (0.5 * (load(r, i - 1) + load(r, i)));
      out[k] += c * state[0];
    }
  }
  return out;
}

}  // namespace mtacc
