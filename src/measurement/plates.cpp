#include "mtacc/measurement/plates.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"

namespace mtacc {
namespace {

std::vector<std::pair<int, int>> probedFeatures(const Plate& plate, PlateFeatures which) {
  std::vector<std::pair<int, int>> f;
  for (int r = 0; r < plate.rows; ++r)
    for (int c = 0; c < plate.columns; ++c)
      if (which == PlateFeatures::All || r == 0 || c == 0 || r == plate.rows - 1 || c == plate.columns - 1) f.emplace_back(r, c);
  return f;
}

// The in-plane displacement of a feature at plate coordinates c for a unit rotation about the
// plate normal.
Vec3 toolPointError(const KinematicModel& actual, const KinematicModel& nominal, const double* q, const Vec3& stylus) {
  return toolInWorkpiece(actual, q) * stylus - toolInWorkpiece(nominal, q) * stylus;
}

}  // namespace

Eigen::Vector2d Plate::centre(int row, int column) const {
  if (!calibrated.empty()) return calibrated[static_cast<size_t>(row * columns + column)];
  return {pitch * column, pitch * row};
}

PlatePoses platePoses(const KinematicModel& nominal, const Plate& plate, const PlatePlacement& placement) {
  const Machine& m = *nominal.machine;
  std::vector<double> hint = placement.fixedAxes;
  if (hint.empty()) hint = m.referencePose;
  if (hint.size() != static_cast<size_t>(m.commandedCount())) throw InvalidInput("plate placement: one fixed position per axis");
  const Pose tool = toolInWorkpiece(nominal, hint.data());
  const Vec3 direction = tool.linear() * m.toolDirection;
  PlatePoses p;
  p.features = probedFeatures(plate, placement.features);
  p.q.resize(static_cast<Eigen::Index>(p.features.size()), m.commandedCount());
  IkOptions options;
  options.hint = hint;
  for (size_t k = 0; k < p.features.size(); ++k) {
    const auto [row, column] = p.features[k];
    const Eigen::Vector2d c = plate.centre(row, column);
    const Vec3 feature = placement.origin + c.x() * placement.u + c.y() * placement.v;
    IkSolution s;
    try {
      s = solveIk(nominal, feature - tool.linear() * placement.stylus, direction, options);
    } catch (const UnreachablePose& e) {
      throw UnreachablePose(fmt::format("plate '{}', feature ({}, {}): {}", placement.name, row, column, e.what()));
    }
    for (int a = 0; a < m.commandedCount(); ++a) {
      if (m.axes[static_cast<size_t>(a)].isRotary() && std::abs(s.q[static_cast<size_t>(a)] - hint[static_cast<size_t>(a)]) > 1e-9)
        throw UnreachablePose(fmt::format("plate '{}', feature ({}, {}): needs {} to turn", placement.name, row, column,
                                          m.axes[static_cast<size_t>(a)].name));
      p.q(static_cast<Eigen::Index>(k), a) = s.q[static_cast<size_t>(a)];
    }
  }
  return p;
}

std::vector<PlatePlacement> cubePlacements(const KinematicModel& nominal, const Plate& plate, double stylus) {
  const Machine& m = *nominal.machine;
  std::vector<double> q = m.referencePose;
  Vec3 low = Vec3::Constant(INFINITY), high = Vec3::Constant(-INFINITY);
  std::vector<int> linear;
  for (int a = 0; a < m.commandedCount(); ++a)
    if (!m.axes[static_cast<size_t>(a)].isRotary() && m.axes[static_cast<size_t>(a)].travel) linear.push_back(a);
  for (int corner = 0; corner < (1 << linear.size()); ++corner) {
    for (size_t k = 0; k < linear.size(); ++k) {
      const auto& travel = *m.axes[static_cast<size_t>(linear[k])].travel;
      q[static_cast<size_t>(linear[k])] = (corner >> k) & 1 ? travel.max : travel.min;
    }
    const Vec3 p = toolInWorkpiece(nominal, q.data()).translation();
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double size = plate.pitch * (std::max(plate.rows, plate.columns) - 1);
  std::vector<PlatePlacement> out;
  const char* axisNames = "XYZ";
  for (const auto& [a, b] : {std::pair{0, 1}, {0, 2}, {1, 2}}) {
    const int normal = 3 - a - b;
    for (const double level : {0.25, 0.75})
      for (const double ua : {0.0, 1.0})
        for (const double vb : {0.0, 1.0}) {
          PlatePlacement p;
          p.name = std::string{axisNames[a], axisNames[b]} + std::to_string(out.size() + 1);
          for (const int k : {a, b})
            if (high[k] - low[k] < size - 1e-9) throw InvalidInput(p.name + ": the plate is larger than the travel");
          p.u = Vec3::Unit(a);
          p.v = Vec3::Unit(b);
          p.origin[a] = low[a] + ua * (high[a] - low[a] - size);
          p.origin[b] = low[b] + vb * (high[b] - low[b] - size);
          p.origin[normal] = low[normal] + level * (high[normal] - low[normal]);
          // The stylus in the tool frame: the normal, turned from the workpiece frame.
          if (level > 0.5) p.stylus = toolInWorkpiece(nominal, m.referencePose.data()).linear().transpose() * (stylus * Vec3::Unit(normal));
          p.fixedAxes = m.referencePose;
          out.push_back(p);
        }
  }
  return out;
}

Eigen::MatrixX2d simulatePlate(const KinematicModel& actual, const KinematicModel& nominal, const Plate&, const PlatePlacement& placement,
                               const PlatePoses& poses) {
  // The probe triggers where the actual stylus touches the feature, and the machine reports
  // where its nominal model puts the stylus then: measured - true = -(actual - nominal).
  const auto n = static_cast<Eigen::Index>(poses.features.size());
  Eigen::MatrixX2d d(n, 2);
  const Vec3 reference = toolPointError(actual, nominal, poses.q.row(0).data(), placement.stylus);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vec3 e = toolPointError(actual, nominal, poses.q.row(k).data(), placement.stylus) - reference;
    d(k, 0) = -placement.u.dot(e);
    d(k, 1) = -placement.v.dot(e);
  }
  return d;
}

Eigen::MatrixX2d withoutMisalignment(const Eigen::MatrixX2d& d, const std::vector<Eigen::Vector2d>& positions) {
  // d ~ t + phi * turn(c): three columns, solved by least squares.
  const auto n = d.rows();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 3);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector2d t = inPlaneTurn(positions[static_cast<size_t>(k)]);
    a(2 * k, 0) = 1.0;
    a(2 * k + 1, 1) = 1.0;
    a(2 * k, 2) = t.x();
    a(2 * k + 1, 2) = t.y();
    b[2 * k] = d(k, 0);
    b[2 * k + 1] = d(k, 1);
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  const Eigen::VectorXd r = b - a * x;
  Eigen::MatrixX2d out(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) out.row(k) << r[2 * k], r[2 * k + 1];
  return out;
}

std::vector<Eigen::Vector2d> featurePositions(const Plate& plate, const std::vector<std::pair<int, int>>& features) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& [row, column] : features)
    out.push_back(plate.centre(row, column) - plate.centre(features[0].first, features[0].second));
  return out;
}

Eigen::MatrixX2d temperatureCorrectedDeviations(const Plate& plate, const std::vector<std::pair<int, int>>& features,
                                                const Eigen::MatrixX2d& measured, const PlateTemperatures& t) {
  if (measured.rows() != static_cast<Eigen::Index>(features.size())) throw InvalidInput("plate deviations: one row per feature");
  const double scale = 1.0 + t.scaleExpansion * (t.scale - t.reference);
  const double grows = 1.0 + t.plateExpansion * (t.plate - t.reference);
  const auto nominal = featurePositions(plate, features);
  Eigen::MatrixX2d d(measured.rows(), 2);
  for (size_t k = 0; k < features.size(); ++k)
    d.row(static_cast<Eigen::Index>(k)) = (measured.row(static_cast<Eigen::Index>(k)).transpose() * scale - nominal[k] * grows).transpose();
  return d;
}

Eigen::MatrixX2d plateDeviations(const Plate& plate, const std::vector<std::pair<int, int>>& features, const Eigen::MatrixX2d& measured,
                                 const PlateTemperatures& t) {
  return withoutMisalignment(temperatureCorrectedDeviations(plate, features, measured, t), featurePositions(plate, features));
}

Eigen::Vector2d inPlaneTurn(const Eigen::Vector2d& c) { return {-c.y(), c.x()}; }

double residualBound(const ResidualBudget& b) {
  const double perFeature = b.plate * b.plate + b.probeU * b.probeU + b.probeV * b.probeV + b.scaleCorrection * b.scaleCorrection +
                            b.plateCorrection * b.plateCorrection;
  return std::sqrt(b.simulation * b.simulation + 2.0 * perFeature);
}

}  // namespace mtacc
