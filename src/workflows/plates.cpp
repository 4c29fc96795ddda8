#include "mtacc/workflows/plates.hpp"

#include <algorithm>
#include <random>

#include "mtacc/core/units.hpp"
#include "mtacc/workflows/artefacts.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/core/text_file.hpp"

#include <fmt/format.h>

namespace mtacc {


const OptionSchema& plateSimulationSchema() {
  static const OptionSchema schema{
      "simulate plate",
      {{.key = "output", .kind = OptionKind::Text, .help = "CSV to write (atomically)", .required = true},
       {.key = "origin", .kind = OptionKind::Text, .help = "reference feature in the workpiece frame, e.g. -350,-455,-160mm", .required = true},
       {"axes", OptionKind::Text, "plate u and v axes in the workpiece frame", "1,0,0 / 0,1,0"},
       {"stylus", OptionKind::Text, "probe tip relative to the TCP, tool frame", "0,0,0 mm"},
       {"plate", OptionKind::Text, "plate layout", "9 x 9, pitch 50 mm"},
       {"features", OptionKind::Text, "all or outer", "all"},
       {"pose", OptionKind::Text, "positions of the axes that stay, e.g. B=0,C=0"},
       {"probe", OptionKind::Text, "2S of the probe along u and v to state in the file, e.g. '1.1, 0.8 um'"},
       {"simulation", OptionKind::Text, "2S of the model's prediction to state in the file, e.g. '6.3 um'"},
       {"noise", OptionKind::Text, "standard deviation of each measured coordinate", "0 um"},
       {.key = "seed", .kind = OptionKind::Count, .help = "random seed", .defaultText = "1", .low = 0, .high = 2147483647,
        .outOfRange = "must be from 0 to 2147483647"}}};
  return schema;
}

PlateSimulationRequest plateSimulationRequest(const OptionValues& values) {
  const OptionReader read(plateSimulationSchema(), values);
  PlateSimulationRequest r;
  r.output = *read.text("output");
  for (const char* key : {"origin", "axes", "stylus", "plate", "features", "pose", "probe", "simulation"})
    if (const auto text = read.text(key)) plateLayoutField(r.layout, key) = *text;
  r.noise = *read.text("noise");
  r.seed = static_cast<std::uint64_t>(*read.count("seed"));
  return r;
}

const OptionSchema& plateComparisonSchema() {
  static const OptionSchema schema{
      "plate", {{.key = "data", .kind = OptionKind::Text, .help = "plate measurement CSV (docs/file-formats.md \"Plate measurements\")", .positional = true}}};
  return schema;
}

PlateComparison comparePlateFile(const MachineSetup& setup, const std::string& path) {
  PlateComparison c;
  c.machine = setup.machine;
  c.measurement = readPlateMeasurement(*setup.machine, path);
  const auto& m = c.measurement;
  const auto e = evaluateArtefact(setup, artefactFromPlate(m));
  c.poses = {m.features, e.poses};
  c.nominal = featurePositions(m.plate, m.features);
  c.measured = e.measured.deviations;
  c.simulated = e.simulated.deviations;
  c.residual = e.residual;
  if (m.probe && m.simulation) {
    c.bound = residualBound({.simulation = *m.simulation, .plate = 2 * m.plate.calibrationUncertainty, .probeU = m.probe->x(),
                             .probeV = m.probe->y(), .scaleCorrection = 0.0, .plateCorrection = 0.0});
    c.beyond = static_cast<int>((c.residual.array().abs() > *c.bound).count());
  }
  return c;
}

nlohmann::json toJson(const PlateComparison& c) {
  nlohmann::json features = nlohmann::json::array();
  for (size_t k = 0; k < c.poses.features.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    features.push_back({{"row", c.poses.features[k].first},
                        {"column", c.poses.features[k].second},
                        {"nominal_mm", {c.nominal[k].x(), c.nominal[k].y()}},
                        {"measured_um", {c.measured(i, 0) * 1e3, c.measured(i, 1) * 1e3}},
                        {"simulated_um", {c.simulated(i, 0) * 1e3, c.simulated(i, 1) * 1e3}},
                        {"residual_um", {c.residual(i, 0) * 1e3, c.residual(i, 1) * 1e3}},
                        {"axes", poseJson(*c.machine, c.poses.q.row(i).data())}});
  }
  const auto& p = c.measurement.placement;
  return {{"file", c.measurement.file},
          {"plate", {{"rows", c.measurement.plate.rows}, {"columns", c.measurement.plate.columns}, {"pitch_mm", c.measurement.plate.pitch}}},
          {"origin_mm", vectorJson(p.origin)},
          {"u", vectorJson(p.u)},
          {"v", vectorJson(p.v)},
          {"stylus_mm", vectorJson(p.stylus)},
          {"features", features},
          {"residual_rms_um", std::sqrt(c.residual.squaredNorm() / static_cast<double>(2 * c.residual.rows())) * 1e3},
          {"residual_max_um", c.residual.cwiseAbs().maxCoeff() * 1e3},
          {"bound_um", c.bound ? nlohmann::json(*c.bound * 1e3) : nlohmann::json(nullptr)},
          {"beyond_bound", c.beyond}};
}

const OptionSchema& plateIdentificationSchema() {
  static const OptionSchema schema{
      "plate-identify",
      {{.key = "files", .kind = OptionKind::List, .help = "Plate measurement CSVs, one per placement", .positional = true},
       {.key = "piece", .kind = OptionKind::Number, .help = "Length of the pieces of the identified functions [mm]", .defaultText = "100",
        .low = 1, .high = 10000, .outOfRange = "a piece length from 1 to 10000 mm"}}};
  return schema;
}

PlateIdentificationRequest plateIdentificationRequest(const OptionValues& values) {
  const OptionReader read(plateIdentificationSchema(), values);
  return {read.list("files"), *read.number("piece")};
}

PlateIdentificationStudy identifyPlateFiles(const MachineSetup& setup, const std::vector<std::string>& files, double pieceLength) {
  if (files.empty()) throw InputError(InputLocation{"", 0, "files"}, "no plate measurements");
  requireInRange(plateIdentificationSchema().at("piece"), pieceLength);
  PlateIdentificationStudy s;
  s.machine = setup.machine;
  s.files = files;
  const auto nominal = setup.nominal();
  ArtefactCampaign campaign;
  for (const auto& file : files) campaign.push_back(campaignPlacement(nominal, readArtefactOrPlate(*setup.machine, file)));
  s.weighted = std::all_of(campaign.begin(), campaign.end(), [](const CampaignPlacement& c) { return c.noise.size() > 0; });
  const ErrorModel shape = plateShape(*setup.machine, ErrorModel::zero(*setup.machine), pieceLength);
  s.parameters = plateParameters(*setup.machine, shape);
  s.result = identifyFromArtefacts(setup.machine, shape, s.parameters, campaign);
  s.identified = shape;
  for (size_t k = 0; k < s.parameters.size(); ++k) setParameterValue(s.identified, s.parameters[k], s.result.values[static_cast<Eigen::Index>(k)]);
  s.yaml = errorsYaml(*setup.machine, s.identified);
  return s;
}

nlohmann::json toJson(const PlateIdentificationStudy& s) {
  nlohmann::json estimates = nlohmann::json::array();
  for (size_t k = 0; k < s.result.names.size(); ++k) {
    const bool machine = k < s.parameters.size();
    const bool angle = machine ? s.parameters[k].dimension == Dimension::Angle : isNuisanceRotation(s.result.names[k]);
    const double unit = angle ? 1e6 : 1e3;
    // Undetermined: the minimum-norm share of a group the plates cannot separate, or 0 for a
    // parameter without effect, with no uncertainty to state.
    const bool determined = s.result.determined[k];
    estimates.push_back({{"name", s.result.names[k]},
                         {"value", s.result.values[static_cast<Eigen::Index>(k)] * unit},
                         {"uncertainty", determined ? nlohmann::json(s.result.uncertainty[static_cast<Eigen::Index>(k)] * unit)
                                                    : nlohmann::json(nullptr)},
                         {"unit", angle ? "urad" : "um"},
                         {"determined", determined}});
  }
  return {{"files", s.files},
          {"readings", s.result.readings},
          {"degrees_of_freedom", s.result.degreesOfFreedom},
          {"weighted", !s.result.names.empty() && s.weighted},
          {s.weighted ? "sigma_over_probe_noise" : "sigma_um", s.weighted ? s.result.sigma : s.result.sigma * 1e3},
          {"rank", s.result.observability.rank},
          {"estimates", estimates},
          {"findings", s.result.observability.findings()},
          {"yaml", s.yaml}};
}

namespace {

// The fields written as a plate file's header and read by its reader: one parser for both.
PlateMeasurement plateLayout(const Machine& machine, const PlateLayoutFields& f) {
  std::string header = "# plate: " + f.plate + "\n# features: " + f.features + "\n# origin: " + f.origin + "\n# axes: " + f.axes +
                       "\n# stylus: " + f.stylus + "\n";
  if (!f.pose.empty()) header += "# pose: " + f.pose + "\n";
  if (!f.probe.empty()) header += "# probe: " + f.probe + "\n";
  if (!f.simulation.empty()) header += "# simulation: " + f.simulation + "\n";
  try {
    return parsePlateLayout(machine, header, "layout");
  } catch (const InputError& e) {
    throw InputError(InputLocation{"", 0, e.where().key}, e.reason());
  }
}

}  // namespace

std::string& plateLayoutField(PlateLayoutFields& f, const std::string& key) {
  for (auto [name, field] : {std::pair{"plate", &f.plate}, {"features", &f.features}, {"origin", &f.origin}, {"axes", &f.axes},
                             {"stylus", &f.stylus}, {"pose", &f.pose}, {"probe", &f.probe}, {"simulation", &f.simulation}})
    if (key == name) return *field;
  throw InputError(InputLocation{"", 0, key}, "not a field of a plate layout (plate, features, origin, axes, stylus, pose, probe, simulation)");
}

PlateMeasurement simulatePlateFile(const MachineSetup& setup, const PlateSimulationRequest& r) {
  PlateMeasurement m = plateLayout(*setup.machine, r.layout);
  if (m.placement.fixedAxes.empty()) m.placement.fixedAxes = setup.machine->referencePose;
  const double noise = parseQuantityAs(r.noise, Dimension::Length, "noise");
  if (!(noise >= 0.0 && noise < 1.0)) throw InputError(InputLocation{"", 0, "noise"}, "from 0 to 1 mm");
  const auto nominal = setup.nominal(), actual = setup.actual();
  const auto poses = platePoses(nominal, m.plate, m.placement);
  const auto d = simulatePlate(actual, nominal, m.plate, m.placement, poses);
  std::mt19937_64 rng(r.seed);
  std::normal_distribution<double> g(0.0, 1.0);
  m.features = poses.features;
  m.measured.resize(d.rows(), 2);
  const auto nominalPositions = featurePositions(m.plate, poses.features);
  for (Eigen::Index k = 0; k < d.rows(); ++k) {
    const Eigen::Vector2d& c = nominalPositions[static_cast<size_t>(k)];
    m.measured.row(k) = (c + d.row(k).transpose() + (k == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(noise * g(rng), noise * g(rng)))).transpose();
  }
  m.file = r.output;
  writeFileAtomically(r.output, plateMeasurementCsv(*setup.machine, m));
  return m;
}

}  // namespace mtacc
