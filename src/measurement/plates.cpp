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

}  // namespace

Eigen::Vector2d Plate::centre(int row, int column) const {
  if (!calibrated.empty()) return calibrated[static_cast<size_t>(row * columns + column)];
  return {pitch * column, pitch * row};
}

Artefact plateArtefact(const Plate& plate, const std::vector<std::pair<int, int>>& features) {
  Artefact a;
  a.name = fmt::format("{} x {} plate, pitch {} mm", plate.rows, plate.columns, plate.pitch);
  a.dimension = 2;
  const auto positions = featurePositions(plate, features);
  for (size_t k = 0; k < features.size(); ++k)
    a.features.push_back({fmt::format("R{}C{}", features[k].first, features[k].second), Vec3(positions[k].x(), positions[k].y(), 0.0),
                          plate.calibrationUncertainty});
  return a;
}

ArtefactPlacement artefactPlacement(const Plate& plate, const PlatePlacement& p) {
  // The artefact's frame starts at the reference feature (0, 0), the plate's at its grid origin.
  const Eigen::Vector2d reference = plate.centre(0, 0);
  return {.name = p.name, .origin = p.origin + reference.x() * p.u + reference.y() * p.v, .u = p.u, .v = p.v, .stylus = p.stylus,
          .fixedAxes = p.fixedAxes, .probed = ProbedDirections::InPlane};
}

PlatePoses platePoses(const KinematicModel& nominal, const Plate& plate, const PlatePlacement& placement) {
  PlatePoses p;
  p.features = probedFeatures(plate, placement.features);
  p.q = artefactPoses(nominal, plateArtefact(plate, p.features), artefactPlacement(plate, placement));
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

Eigen::MatrixX2d simulatePlate(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate, const PlatePlacement& placement,
                               const PlatePoses& poses) {
  const Eigen::MatrixX3d e = artefactProbingErrors(actual, nominal, artefactPlacement(plate, placement), poses.q);
  const Eigen::MatrixX3d relative = e.rowwise() - e.row(0);
  Eigen::MatrixX2d d(e.rows(), 2);
  d << relative * placement.u, relative * placement.v;
  return d;
}

std::vector<Eigen::Vector2d> featurePositions(const Plate& plate, const std::vector<std::pair<int, int>>& features) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& [row, column] : features)
    out.push_back(plate.centre(row, column) - plate.centre(features[0].first, features[0].second));
  return out;
}

double residualBound(const ResidualBudget& b) {
  const double perFeature = b.plate * b.plate + b.probeU * b.probeU + b.probeV * b.probeV + b.scaleCorrection * b.scaleCorrection +
                            b.plateCorrection * b.plateCorrection;
  return std::sqrt(b.simulation * b.simulation + 2.0 * perFeature);
}

}  // namespace mtacc
