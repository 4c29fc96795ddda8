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

std::vector<Vec3> nuisanceRotations(const CampaignPlacement& c) {
  const auto& p = c.placement;
  switch (p.probed) {
    case ProbedDirections::Along: return {};
    case ProbedDirections::InPlane: return {p.u.cross(p.v)};
    case ProbedDirections::All: break;
  }
  if (c.dimension == 1) return {p.v, p.u.cross(p.v)};
  return {p.u, p.v, p.u.cross(p.v)};
}

bool isNuisanceRotation(const std::string& name) {
  return name.size() > 3 && name[name.size() - 3] == '.' && name[name.size() - 2] == 'r';
}

CampaignPlacement plateCampaignPlacement(const Plate& plate, const PlatePlacement& placement, const PlatePoses& poses,
                                         const Eigen::MatrixX2d& deviations, const Eigen::Vector2d& noise) {
  CampaignPlacement c{.placement = artefactPlacement(plate, placement), .dimension = 2, .positions = {}, .poses = poses.q,
                      .deviations = deviations, .noise = noise};
  const auto positions = featurePositions(plate, poses.features);
  c.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (size_t k = 0; k < positions.size(); ++k)
    c.positions.row(static_cast<Eigen::Index>(k)) = (positions[k].x() * placement.u + positions[k].y() * placement.v).transpose();
  return c;
}

ArtefactCampaign simulatePlateCampaign(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate,
                                       const std::vector<PlatePlacement>& placements, const std::vector<Eigen::Vector2d>& noise,
                                       std::uint64_t seed) {
  if (noise.size() != placements.size()) throw InvalidInput("plate campaign: noise per placement");
  ArtefactCampaign c;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (size_t k = 0; k < placements.size(); ++k) {
    const auto poses = platePoses(nominal, plate, placements[k]);
    Eigen::MatrixX2d d = simulatePlate(actual, nominal, plate, placements[k], poses);
    for (Eigen::Index i = 0; i < d.rows(); ++i) d.row(i) += Eigen::RowVector2d(noise[k][0] * unit(rng), noise[k][1] * unit(rng));
    c.push_back(plateCampaignPlacement(plate, placements[k], poses, d, noise[k]));
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

namespace {

const char* const kDirections[] = {"u", "v", "w"};

int nuisanceCount(const CampaignPlacement& c) {
  return directionCount(c.placement.probed) + static_cast<int>(nuisanceRotations(c).size());
}

}  // namespace

Eigen::MatrixXd artefactDesignMatrix(const KinematicModel& model, const ArtefactCampaign& campaign, int threads) {
  const auto parameters = static_cast<Eigen::Index>(model.parameters.size());
  std::vector<Eigen::Index> firstRow{0}, firstNuisance{parameters};
  for (const auto& c : campaign) {
    firstRow.push_back(firstRow.back() + directionCount(c.placement.probed) * c.poses.rows());
    firstNuisance.push_back(firstNuisance.back() + nuisanceCount(c));
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(firstRow.back(), firstNuisance.back());
  // One task per feature across the campaign; each thread keeps its own scratch.
  std::vector<std::pair<size_t, Eigen::Index>> tasks;
  for (size_t k = 0; k < campaign.size(); ++k)
    for (Eigen::Index h = 0; h < campaign[k].poses.rows(); ++h) tasks.emplace_back(k, h);
  parallelFor(static_cast<long>(tasks.size()), threads, [&](long begin, long end) {
    KinematicData data;
    for (long t = begin; t < end; ++t) {
      const auto [k, h] = tasks[static_cast<size_t>(t)];
      const auto& c = campaign[k];
      const int directions = directionCount(c.placement.probed);
      const Eigen::Matrix3d frame = c.placement.frame();
      const auto& j = pointJacobian(model, c.poses.row(h).data(), nullptr, c.placement.stylus, data).jacobian;
      const auto rotations = nuisanceRotations(c);
      const Vec3 p = c.positions.row(h).transpose();
      for (int d = 0; d < directions; ++d) {
        const Eigen::Index row = firstRow[k] + directions * h + d;
        const Vec3 along = frame.col(d);
        a.block(row, 0, 1, parameters).noalias() = -along.transpose() * j;
        a(row, firstNuisance[k] + d) = 1.0;
        for (size_t r = 0; r < rotations.size(); ++r) a(row, firstNuisance[k] + directions + static_cast<Eigen::Index>(r)) = along.dot(rotations[r].cross(p));
      }
    }
  });
  return a;
}

PlateIdentification identifyFromArtefacts(const std::shared_ptr<const Machine>& machine, const ErrorModel& shape,
                                          const std::vector<Parameter>& parameters, const ArtefactCampaign& campaign, int threads) {
  bool weighted = !campaign.empty();
  for (const auto& c : campaign) {
    const int directions = directionCount(c.placement.probed);
    if (c.positions.rows() != c.poses.rows() || c.deviations.rows() != c.poses.rows() || c.deviations.cols() != directions)
      throw InvalidInput("artefact campaign: positions, poses and deviations for every feature");
    if (c.noise.size() != 0 && c.noise.size() != directions) throw InvalidInput("artefact campaign: noise per probed direction");
    weighted = weighted && c.noise.size() == directions && (c.noise.array() > 0.0).all();
  }
  ErrorModel zero = shape;
  for (const auto& p : parameterCatalogue(*machine, zero)) setParameterValue(zero, p, 0.0);
  const auto model = compile(machine, zero, parameters);
  Eigen::MatrixXd a = artefactDesignMatrix(model, campaign, threads);
  Eigen::VectorXd b(a.rows());
  Eigen::Index row = 0;
  for (const auto& c : campaign)
    for (Eigen::Index k = 0; k < c.deviations.rows(); ++k)
      for (Eigen::Index d = 0; d < c.deviations.cols(); ++d, ++row) {
        const double w = weighted ? 1.0 / c.noise[d] : 1.0;
        b[row] = w * c.deviations(k, d);
        a.row(row) *= w;
      }
  PlateIdentification out;
  for (const auto& p : parameters) out.names.push_back(p.name);
  for (const auto& c : campaign) {
    for (int d = 0; d < directionCount(c.placement.probed); ++d) out.names.push_back(c.placement.name + ".t" + kDirections[d]);
    const Eigen::Matrix3d frame = c.placement.frame();
    for (const Vec3& r : nuisanceRotations(c)) {
      Eigen::Index about = 0;
      (frame.transpose() * r).cwiseAbs().maxCoeff(&about);
      out.names.push_back(c.placement.name + ".r" + kDirections[about]);
    }
  }
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
