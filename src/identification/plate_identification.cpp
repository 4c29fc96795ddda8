#include "mtacc/identification/plate_identification.hpp"

#include <cmath>
#include <random>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {

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
      const Eigen::Vector2d spin = inPlaneTurn(campaign.plate.centre(r, c) - campaign.plate.centre(r0, c0));
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
