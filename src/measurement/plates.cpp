#include "mtacc/measurement/plates.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>

#include <cmath>
#include <cstdio>
#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/jacobian.hpp"

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
Eigen::Vector2d turn(const Eigen::Vector2d& c) { return {-c.y(), c.x()}; }

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
    const Eigen::Vector2d t = turn(positions[static_cast<size_t>(k)]);
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

double residualBound(const ResidualBudget& b) {
  const double perFeature = b.plate * b.plate + b.probeU * b.probeU + b.probeV * b.probeV + b.scaleCorrection * b.scaleCorrection +
                            b.plateCorrection * b.plateCorrection;
  return std::sqrt(b.simulation * b.simulation + 2.0 * perFeature);
}

ErrorModel plateShape(const Machine& machine, const ErrorModel& known, double pieceLength) {
  ErrorModel shape = known;
  for (const char* name : {"X", "Y", "Z"}) {
    const int a = machine.axisIndex(name);
    if (a < 0 || !machine.axes[static_cast<size_t>(a)].travel) continue;
    const auto& travel = *machine.axes[static_cast<size_t>(a)].travel;
    const int pieces = std::max(1, static_cast<int>(std::round((travel.max - travel.min) / pieceLength)));
    std::vector<double> breaks;
    for (int i = 0; i <= pieces; ++i) breaks.push_back(travel.min + (travel.max - travel.min) * i / pieces);
    for (auto& f : shape.axes[static_cast<size_t>(a)].motion)
      if (f.empty()) f.add(continuousPiecewise(breaks));
  }
  return shape;
}

std::vector<Eigen::Vector2d> seed003ProbeNoise(const std::vector<PlatePlacement>& placements) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : placements) {
    const Vec3 normal = p.u.cross(p.v).cwiseAbs();
    const Eigen::Vector2d twoS = normal.z() > 0.5 ? Eigen::Vector2d(1.1, 0.8) : normal.y() > 0.5 ? Eigen::Vector2d(0.63, 0.84) : Eigen::Vector2d(1.4, 7.5);
    out.push_back(0.5e-3 * twoS);
  }
  return out;
}

PlateCampaign simulatePlateCampaign(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate,
                                    const std::vector<PlatePlacement>& placements, const std::vector<Eigen::Vector2d>& noise,
                                    std::uint64_t seed) {
  if (noise.size() != placements.size()) throw InvalidInput("plate campaign: noise per placement");
  PlateCampaign c;
  c.plate = plate;
  c.placements = placements;
  c.noise = noise;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (size_t k = 0; k < placements.size(); ++k) {
    c.poses.push_back(platePoses(nominal, plate, placements[k]));
    Eigen::MatrixX2d d = simulatePlate(actual, nominal, plate, placements[k], c.poses.back());
    for (Eigen::Index i = 0; i < d.rows(); ++i) d.row(i) += Eigen::RowVector2d(noise[k][0] * unit(rng), noise[k][1] * unit(rng));
    c.deviations.push_back(d);
  }
  return c;
}

std::vector<Parameter> plateParameters(const Machine& machine, const ErrorModel& shape) {
  std::vector<Parameter> out;
  const int x = machine.axisIndex("X"), y = machine.axisIndex("Y"), z = machine.axisIndex("Z");
  for (const auto& p : parameterCatalogue(machine, shape)) {
    if (p.axis != x && p.axis != y && p.axis != z) continue;
    if (p.kind == ParameterKind::Location) {
      if ((p.axis == y && p.name == "C0Y") || (p.axis == z && (p.name == "B0Z" || p.name == "A0Z"))) out.push_back(p);
      continue;
    }
    // A piecewise term's parameter is named k<knot>c<power>, with #n for the n-th such term.
    const std::string suffix = p.name.substr(p.name.find('.') + 1);
    int knot = 0, power = 0, nth = 1;
    if (std::sscanf(suffix.c_str(), "k%dc%d#%d", &knot, &power, &nth) < 2) continue;
    int degree = 0, seen = 0;
    for (const auto& term : shape.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)].terms())
      if (const auto* piece = std::get_if<PiecewiseTerm>(&term); piece && ++seen == nth)
        for (const auto& c : piece->coefficients) degree = std::max(degree, c.power);
    const bool ownDirection = p.component == machine.axes[static_cast<size_t>(p.axis)].ownComponent();
    if (knot == 0 && power == 0) continue;                                        // constant
    if (knot == 0 && power == 1 && p.component < 3 && !ownDirection) continue;    // a straightness's line
    if (knot > 0 && power < degree) continue;  // value or slope jump of a continuous function
    out.push_back(p);
  }
  return out;
}

Eigen::MatrixXd plateDesignMatrix(const KinematicModel& model, const PlateCampaign& campaign, int threads) {
  const auto parameters = static_cast<Eigen::Index>(model.parameters.size());
  const auto placements = static_cast<Eigen::Index>(campaign.placements.size());
  std::vector<Eigen::Index> firstRow{0};
  for (const auto& p : campaign.poses) firstRow.push_back(firstRow.back() + 2 * static_cast<Eigen::Index>(p.features.size()));
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(firstRow.back(), parameters + 3 * placements);
  // One task per feature across the campaign; each thread keeps its own scratch.
  std::vector<std::pair<Eigen::Index, Eigen::Index>> tasks;
  for (Eigen::Index k = 0; k < placements; ++k)
    for (Eigen::Index h = 0; h < static_cast<Eigen::Index>(campaign.poses[static_cast<size_t>(k)].features.size()); ++h) tasks.emplace_back(k, h);
  parallelFor(static_cast<long>(tasks.size()), threads, [&](long begin, long end) {
    KinematicData data;
    for (long t = begin; t < end; ++t) {
      const auto [k, h] = tasks[static_cast<size_t>(t)];
      const auto& placement = campaign.placements[static_cast<size_t>(k)];
      const auto& poses = campaign.poses[static_cast<size_t>(k)];
      const auto& j = pointJacobian(model, poses.q.row(h).data(), nullptr, placement.stylus, data).jacobian;
      const Eigen::Index row = firstRow[static_cast<size_t>(k)] + 2 * h;
      a.block(row, 0, 1, parameters).noalias() = -placement.u.transpose() * j;
      a.block(row + 1, 0, 1, parameters).noalias() = -placement.v.transpose() * j;
      const auto [r, c] = poses.features[static_cast<size_t>(h)];
      const auto [r0, c0] = poses.features[0];
      const Eigen::Vector2d spin = turn(campaign.plate.centre(r, c) - campaign.plate.centre(r0, c0));
      const Eigen::Index nuisance = parameters + 3 * k;
      a(row, nuisance) = 1.0;
      a(row + 1, nuisance + 1) = 1.0;
      a(row, nuisance + 2) = spin.x();
      a(row + 1, nuisance + 2) = spin.y();
    }
  });
  return a;
}

PlateIdentification identifyFromPlates(const std::shared_ptr<const Machine>& machine, const ErrorModel& shape,
                                       const std::vector<Parameter>& parameters, const PlateCampaign& campaign, int threads) {
  if (campaign.poses.size() != campaign.placements.size() || campaign.deviations.size() != campaign.placements.size())
    throw InvalidInput("plate campaign: poses and deviations for every placement");
  ErrorModel zero = shape;
  for (const auto& p : parameterCatalogue(*machine, zero)) setParameterValue(zero, p, 0.0);
  const auto model = compile(machine, zero, parameters);
  Eigen::MatrixXd a = plateDesignMatrix(model, campaign, threads);
  Eigen::VectorXd b(a.rows());
  const bool weighted = !campaign.noise.empty();
  if (weighted && campaign.noise.size() != campaign.placements.size()) throw InvalidInput("plate campaign: noise per placement");
  Eigen::Index row = 0;
  for (size_t p = 0; p < campaign.deviations.size(); ++p) {
    const auto& d = campaign.deviations[p];
    if (d.rows() != static_cast<Eigen::Index>(campaign.poses[p].features.size()))
      throw InvalidInput("plate campaign: one deviation row per probed feature");
    for (Eigen::Index k = 0; k < d.rows(); ++k)
      for (int c = 0; c < 2; ++c, ++row) {
        const double w = weighted ? 1.0 / campaign.noise[p][c] : 1.0;
        b[row] = w * d(k, c);
        a.row(row) *= w;
      }
  }
  PlateIdentification out;
  for (const auto& p : parameters) out.names.push_back(p.name);
  for (const auto& p : campaign.placements)
    for (const char* n : {".tu", ".tv", ".rot"}) out.names.push_back(p.name + n);
  const Eigen::Index n = a.cols();
  // One QR of [A D^-1 | b] (D the column norms): R and Q^T b. The SVD of the small R gives the
  // minimum-norm solution on the observable subspace, its covariance, and (as R D, which has
  // A's singular values and column norms) the observability report, without squaring A's
  // condition number as normal equations would.
  // A column without effect (a zero column, to rounding) is held at zero: scaled by its tiny norm
  // the solve's rounding would come back as values of 1e289.
  Eigen::VectorXd norms = a.colwise().norm().transpose();
  const double largest = norms.size() > 0 ? norms.maxCoeff() : 0.0;
  std::vector<bool> noEffect(static_cast<size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k)
    if (norms[k] <= 1e-12 * largest) {
      noEffect[static_cast<size_t>(k)] = true;
      a.col(k).setZero();
      norms[k] = 1.0;
    }
  Eigen::MatrixXd augmented(a.rows(), n + 1);
  augmented.leftCols(n) = a * norms.cwiseInverse().asDiagonal();
  augmented.col(n) = b;
  Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(augmented);
  const Eigen::Index k = std::min(augmented.rows(), n + 1);
  const Eigen::MatrixXd r = augmented.topRows(k).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd rn = r.topLeftCorner(std::min(k, n), n);
  const Eigen::VectorXd qtb = r.col(n).head(rn.rows());
  const double outside = k > n ? r(n, n) * r(n, n) : 0.0;  // |b|^2 beyond the columns' span
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(rn, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  int rank = 0;
  while (rank < sv.size() && sv[rank] > kRankTolerance * sv[0]) ++rank;
  const Eigen::MatrixXd v = svd.matrixV().leftCols(rank);
  const Eigen::VectorXd projected = svd.matrixU().leftCols(rank).transpose() * qtb;
  out.values = (v * projected.cwiseQuotient(sv.head(rank))).cwiseQuotient(norms);
  const double residualSquares = outside + (qtb.squaredNorm() - projected.squaredNorm());
  const Eigen::MatrixXd pseudo = v * sv.head(rank).cwiseAbs2().cwiseInverse().asDiagonal() * v.transpose();
  out.readings = static_cast<int>(a.rows());
  out.degreesOfFreedom = out.readings - rank;
  out.sigma = std::sqrt(std::max(0.0, residualSquares) / std::max(1, out.degreesOfFreedom));
  const double scale = weighted ? 1.0 : out.sigma;  // weighted: the stated noise sets the scale
  out.covariance = scale * scale * norms.cwiseInverse().asDiagonal() * pseudo * norms.cwiseInverse().asDiagonal();
  for (Eigen::Index k = 0; k < n; ++k)
    if (noEffect[static_cast<size_t>(k)]) out.values[k] = 0.0;
  out.uncertainty = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  Eigen::VectorXd typical(n);
  for (Eigen::Index k = 0; k < n; ++k) typical[k] = k < static_cast<Eigen::Index>(parameters.size()) && parameters[static_cast<size_t>(k)].dimension == Dimension::Angle ? 1e-5 : 1e-3;
  out.observability = analyseObservability(rn * norms.asDiagonal(), out.names, typical, kRankTolerance, threads);
  out.determined.assign(static_cast<size_t>(n), true);
  for (const auto& name : out.observability.noEffect)
    for (size_t k = 0; k < out.names.size(); ++k)
      if (out.names[k] == name) out.determined[k] = false;
  for (const auto& g : out.observability.groups)
    for (const auto& name : g.names)
      for (size_t k = 0; k < out.names.size(); ++k)
        if (out.names[k] == name) out.determined[k] = false;
  return out;
}

}  // namespace mtacc
