#include "mtacc/workflows/plates.hpp"

#include <random>

#include "mtacc/core/units.hpp"
#include "mtacc/io/text_file.hpp"

namespace mtacc {

PlateComparison comparePlateFile(const MachineSetup& setup, const std::string& path) {
  PlateComparison c;
  c.machine = setup.machine;
  c.measurement = readPlateMeasurement(*setup.machine, path);
  const auto& m = c.measurement;
  const auto nominal = setup.nominal(), actual = setup.actual();
  try {
    c.poses = platePoses(nominal, m.plate, m.placement);
  } catch (const UnreachablePose& e) {
    throw InputError(InputLocation{path, m.originLine, "origin"}, e.what());
  }
  for (const auto& [row, column] : c.poses.features) c.nominal.push_back(m.plate.centre(row, column) - m.plate.centre(0, 0));
  c.measured = plateDeviations(m.plate, m.features, m.measured, m.temperatures);
  c.simulated = withoutMisalignment(simulatePlate(actual, nominal, m.plate, m.placement, c.poses), c.nominal);
  c.residual = c.measured - c.simulated;
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

PlateMeasurement simulatePlateFile(const MachineSetup& setup, const PlateSimulationRequest& r) {
  PlateMeasurement m = r.layout;
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
  for (Eigen::Index k = 0; k < d.rows(); ++k) {
    const auto [row, column] = poses.features[static_cast<size_t>(k)];
    const Eigen::Vector2d c = m.plate.centre(row, column) - m.plate.centre(0, 0);
    m.measured.row(k) = (c + d.row(k).transpose() + (k == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(noise * g(rng), noise * g(rng)))).transpose();
  }
  m.file = r.output;
  writeFileAtomically(r.output, plateMeasurementCsv(*setup.machine, m));
  return m;
}

}  // namespace mtacc
