#include "mtacc/workflows/artefacts.hpp"

#include <fmt/format.h>

#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

const char* const kDirectionNames[] = {"u", "v", "w"};

Eigen::VectorXd certificateSigma(const Artefact& a) {
  Eigen::VectorXd s(static_cast<Eigen::Index>(a.features.size()));
  for (size_t k = 0; k < a.features.size(); ++k) s[static_cast<Eigen::Index>(k)] = a.features[k].uncertainty;
  return s;
}

Vec3 probeSigma(const ArtefactMeasurement& m) {
  Vec3 s = Vec3::Zero();
  for (size_t k = 0; k < m.probe.size(); ++k) s[static_cast<Eigen::Index>(k)] = 0.5 * m.probe[k];
  return s;
}

nlohmann::json row(const Eigen::MatrixXd& m, Eigen::Index i, double unit) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index j = 0; j < m.cols(); ++j) out.push_back(m(i, j) * unit);
  return out;
}

// The artefact's growth and the scales' reading factor at the measurement's temperatures: a
// reading x is s x at the reference temperature, a certificate position c is g c on the machine.
struct Expansion {
  double grows, scale;
};
Expansion expansion(const PlateTemperatures& t) {
  return {1.0 + t.plateExpansion * (t.plate - t.reference), 1.0 + t.scaleExpansion * (t.scale - t.reference)};
}

// The axis positions reaching each feature where it is: the certificate grown at the artefact's
// temperature. One beyond the travel is an error at the file's origin line.
JointMatrix measuredPoses(const KinematicModel& nominal, const ArtefactMeasurement& m) {
  Artefact grown = m.artefact;
  const double grows = expansion(m.temperatures).grows;
  for (auto& f : grown.features) f.calibrated *= grows;
  try {
    return artefactPoses(nominal, grown, m.placement);
  } catch (const UnreachablePose& e) {
    throw UnreachableInput(InputLocation{m.file, m.originLine, "origin"}, e.what());
  }
}

}  // namespace

ArtefactCoordinates artefactCoordinates(const ArtefactMeasurement& m) {
  const auto [grows, scale] = expansion(m.temperatures);
  ArtefactCoordinates c;
  const auto n = static_cast<Eigen::Index>(m.artefact.features.size());
  c.calibrated.resize(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) c.calibrated.row(k) = grows * m.artefact.features[static_cast<size_t>(k)].calibrated.transpose();
  const Eigen::Matrix3d frame = m.placement.frame();
  c.measured = ((scale * m.measured).rowwise() - m.placement.origin.transpose()) * frame;
  return c;
}

const OptionSchema& artefactEvaluationSchema() {
  static const OptionSchema schema{
      "artefact",
      {{.key = "data", .kind = OptionKind::Text, .help = "artefact or plate measurement CSV (docs/file-formats.md \"Artefact measurements\")",
        .positional = true}}};
  return schema;
}

ArtefactEvaluation evaluateArtefactFile(const MachineSetup& setup, const std::string& path) {
  return evaluateArtefact(setup, readArtefactOrPlate(*setup.machine, path));
}

ArtefactEvaluation evaluateArtefact(const MachineSetup& setup, ArtefactMeasurement measurement) {
  ArtefactEvaluation e;
  e.machine = setup.machine;
  e.measurement = std::move(measurement);
  const auto& m = e.measurement;
  const auto nominal = setup.nominal(), actual = setup.actual();
  e.poses = measuredPoses(nominal, m);
  const auto c = artefactCoordinates(m);
  const int dimension = m.artefact.dimension;
  const auto probed = m.placement.probed;
  try {
    e.measured = alignArtefact(c.calibrated, c.measured, probed, dimension, m.alignment);
  } catch (const InvalidInput& error) {
    throw InputError(InputLocation{m.file, m.alignmentLine, "alignment"}, error.what());
  }
  Alignment same = m.alignment;
  same.features = e.measured.features;
  const Eigen::MatrixX3d probing = artefactProbingErrors(actual, nominal, m.placement, e.poses) * m.placement.frame();
  e.simulated = alignArtefact(c.calibrated, c.calibrated + probing, probed, dimension, same);
  e.residual = e.measured.deviations - e.simulated.deviations;
  const Eigen::VectorXd certificate = certificateSigma(m.artefact);
  const Vec3 probe = probeSigma(m);
  e.expanded = deviationUncertainty(c.calibrated, c.measured, probed, dimension, same, certificate, probe);
  e.certificatePart = deviationUncertainty(c.calibrated, c.measured, probed, dimension, same, certificate, Vec3::Zero());
  e.probingPart = deviationUncertainty(c.calibrated, c.measured, probed, dimension, same, Eigen::VectorXd::Zero(certificate.size()), probe);
  e.simulation = m.simulation;
  const Eigen::ArrayXXd bound = (e.expanded.array().square() + std::pow(m.simulation.value_or(0.0), 2)).sqrt();
  e.beyond = static_cast<int>((e.residual.array().abs() > bound).count());
  return e;
}

nlohmann::json toJson(const ArtefactEvaluation& e) {
  const auto& m = e.measurement;
  const auto k = e.measured.deviations.cols();
  const Eigen::Matrix3d frame = m.placement.frame();
  nlohmann::json features = nlohmann::json::array();
  for (size_t h = 0; h < m.artefact.features.size(); ++h) {
    const auto i = static_cast<Eigen::Index>(h);
    nlohmann::json f{{"feature", m.artefact.features[h].id},
                     {"calibrated_mm", vectorJson(m.artefact.features[h].calibrated)},
                     {"measured_mm", vectorJson(m.measured.row(i).transpose())},
                     {"deviation_um", row(e.measured.deviations, i, 1e3)},
                     {"expanded_uncertainty_um", row(e.expanded, i, 1e3)},
                     {"simulated_um", row(e.simulated.deviations, i, 1e3)},
                     {"residual_um", row(e.residual, i, 1e3)},
                     {"axes", poseJson(*e.machine, e.poses.row(i).data())}};
    if (k == 3) f["deviation_xyz_um"] = vectorJson(1e3 * frame * e.measured.deviations.row(i).transpose());
    features.push_back(f);
  }
  nlohmann::json directions = nlohmann::json::array();
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto d = e.measured.deviations.col(j);
    Eigen::Index worst = 0;
    d.cwiseAbs().maxCoeff(&worst);
    directions.push_back({{"direction", kDirectionNames[j]},
                          {"axis_in_workpiece", vectorJson(frame.col(j))},
                          {"largest_um", d[worst] * 1e3},
                          {"largest_feature", m.artefact.features[static_cast<size_t>(worst)].id},
                          {"largest_expanded_uncertainty_um", e.expanded(worst, j) * 1e3},
                          {"rms_um", std::sqrt(d.squaredNorm() / static_cast<double>(d.size())) * 1e3},
                          {"range_um", (d.maxCoeff() - d.minCoeff()) * 1e3},
                          {"simulated_range_um", (e.simulated.deviations.col(j).maxCoeff() - e.simulated.deviations.col(j).minCoeff()) * 1e3},
                          {"residual_rms_um", std::sqrt(e.residual.col(j).squaredNorm() / static_cast<double>(d.size())) * 1e3}});
  }
  const auto& a = e.measured;
  const char* method = m.alignment.method == AlignmentMethod::ThreePoint ? "three-point"
                       : m.alignment.method == AlignmentMethod::LeastSquares ? "least-squares" : "least-squares-scaled";
  nlohmann::json alignment{{"method", method},
                           {"translation_um", row(a.translation.transpose(), 0, 1e3)},
                           {"rotation_urad", k == 1 ? 0.0 : std::acos(std::clamp((a.rotation.trace() - (k == 3 ? 1.0 : 0.0)) / 2.0, -1.0, 1.0)) * 1e6},
                           {"scale_ppm", (a.scale - 1.0) * 1e6}};
  if (m.alignment.method == AlignmentMethod::ThreePoint) {
    nlohmann::json ids = nlohmann::json::array();
    for (const int f : a.features)
      if (f >= 0) ids.push_back(m.artefact.features[static_cast<size_t>(f)].id);
    alignment["features"] = ids;
  }
  const double u = [&] { return e.expanded.size() ? e.expanded.maxCoeff() : 0.0; }();
  return {{"file", m.file},
          {"artefact", m.artefact.name},
          {"dimension", m.artefact.dimension},
          {"probed", k == 3 ? "all" : k == 2 ? "in-plane" : "along"},
          {"origin_mm", vectorJson(m.placement.origin)},
          {"u", vectorJson(m.placement.u)},
          {"v", vectorJson(m.placement.v)},
          {"stylus_mm", vectorJson(m.placement.stylus)},
          {"alignment", alignment},
          {"directions", directions},
          {"uncertainty",
           {{"coverage_factor", 2},
            {"method", fmt::format("Monte Carlo over the alignment (GUM Supplement 1), {} draws", kUncertaintyDraws)},
            {"certificate_stated", m.certificateStated},
            {"probe_stated", !m.probe.empty()},
            {"largest_um", u * 1e3},
            {"certificate_largest_um", e.certificatePart.size() ? e.certificatePart.maxCoeff() * 1e3 : 0.0},
            {"probing_largest_um", e.probingPart.size() ? e.probingPart.maxCoeff() * 1e3 : 0.0},
            {"model_2s_um", e.simulation ? nlohmann::json(*e.simulation * 1e3) : nlohmann::json(nullptr)}}},
          {"beyond_bound", e.beyond},
          {"features", features}};
}

CampaignPlacement campaignPlacement(const KinematicModel& nominal, const ArtefactMeasurement& m) {
  const auto c = artefactCoordinates(m);
  CampaignPlacement p{.placement = m.placement, .dimension = m.artefact.dimension, .positions = {}, .poses = measuredPoses(nominal, m),
                      .deviations = alignArtefact(c.calibrated, c.measured, m.placement.probed, m.artefact.dimension, {}).deviations,
                      .noise = {}};
  p.positions = (c.calibrated.rowwise() - c.calibrated.row(0)) * m.placement.frame().transpose();
  if (!m.probe.empty()) p.noise = 0.5 * Eigen::Map<const Eigen::VectorXd>(m.probe.data(), static_cast<Eigen::Index>(m.probe.size()));
  return p;
}

const OptionSchema& artefactSimulationSchema() {
  static const OptionSchema schema{
      "simulate artefact",
      {{.key = "layout", .kind = OptionKind::Text, .help = "artefact file without measured values (docs/file-formats.md)", .required = true},
       {.key = "output", .kind = OptionKind::Text, .help = "CSV to write (atomically)", .required = true},
       {"noise", OptionKind::Text, "standard deviation of each measured coordinate", "0 um"},
       {.key = "seed", .kind = OptionKind::Count, .help = "random seed", .defaultText = "1", .low = 0, .high = 2147483647,
        .outOfRange = "must be from 0 to 2147483647"}}};
  return schema;
}

ArtefactSimulationRequest artefactSimulationRequest(const OptionValues& values) {
  const OptionReader read(artefactSimulationSchema(), values);
  return {*read.text("layout"), *read.text("output"), *read.text("noise"), static_cast<std::uint64_t>(*read.count("seed"))};
}

ArtefactMeasurement simulateArtefactFile(const MachineSetup& setup, const ArtefactSimulationRequest& r) {
  ArtefactMeasurement m = readArtefactMeasurement(*setup.machine, r.layout);
  if (m.measured.rows() > 0)
    throw InputError(InputLocation{r.layout, m.featureLines.front(), "x"}, "a layout has no measured values (leave x, y, z empty)");
  const double noise = parseQuantityAs(r.noise, Dimension::Length, "noise");
  if (!(noise >= 0.0 && noise < 1.0)) throw InputError(InputLocation{"", 0, "noise"}, "from 0 to 1 mm");
  const auto nominal = setup.nominal(), actual = setup.actual();
  const auto poses = measuredPoses(nominal, m);
  const Eigen::MatrixX3d errors = artefactProbingErrors(actual, nominal, m.placement, poses);
  std::mt19937_64 rng(r.seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  // The artefact grown at its temperature, read by scales at theirs.
  const auto [grows, scale] = expansion(m.temperatures);
  m.measured.resize(errors.rows(), 3);
  for (Eigen::Index k = 0; k < errors.rows(); ++k)
    m.measured.row(k) = ((m.placement.place(grows * m.artefact.features[static_cast<size_t>(k)].calibrated) + errors.row(k).transpose() +
                          noise * Vec3(unit(rng), unit(rng), unit(rng))) /
                         scale)
                            .transpose();
  m.file = r.output;
  writeFileAtomically(r.output, artefactMeasurementCsv(*setup.machine, m));
  return m;
}

}  // namespace mtacc
