#pragma once
// The virtual thermal machine the thermal tests share: seed 003's Maho-like spindle head run
// through seed 003's load cycle (5000 rpm for 6 h, then 8 h at rest, L971-973), and the drift
// test it records (five probes, five temperatures) that data/thermal/maho-spindle-drift.csv holds.
#include <utility>
#include <vector>

#include "mtacc/io/drift_test_csv.hpp"
#include "mtacc/thermal/thermal_machine.hpp"

namespace mtacc::test {

// Nodes: 0 the spindle head (fast), 1 the column (slow), 2 the bed (slower), 3 the spindle motor
// housing (fast, no effect on the drift). Sensors: the room, then one on each node. The drift
// (Y at the lower probes, mm) is 1.5 um/K of the head and 2.5 um/K of the column.
inline VirtualThermalMachine maho(std::uint64_t seed, std::vector<double> driftPerKelvin = {1.5e-3, 2.5e-3, 0, 0}) {
  VirtualThermalMachine m;
  m.nodes = {{1800, {25}}, {3 * 3600, {8}}, {6 * 3600, {3}}, {900, {15}}};
  m.driftPerKelvin = std::move(driftPerKelvin);
  m.sensedNode = {-1, 0, 1, 2, 3};
  m.roomSwing = 0.5;
  m.seed = seed;
  return m;
}

// The spindle at load 1 for `on` hours, then at rest for `off` hours, repeated; `perHour` samples an hour.
inline Eigen::MatrixXd cycle(const std::vector<std::pair<double, double>>& onOff, int perHour = 3600) {
  std::vector<double> load;
  for (const auto& [on, off] : onOff) {
    load.insert(load.end(), static_cast<size_t>(on * perHour), 1.0);
    load.insert(load.end(), static_cast<size_t>(off * perHour), 0.0);
  }
  return Eigen::Map<const Eigen::VectorXd>(load.data(), static_cast<long>(load.size()));
}

// An axis stopping at each of `stops` (mm) in turn for `dwell` samples, over `samples` samples:
// the positions at which an axis-motion drift test reads the drift.
inline Eigen::VectorXd stops(long samples, const std::vector<double>& stops, long dwell) {
  Eigen::VectorXd p(samples);
  for (long k = 0; k < samples; ++k) p[k] = stops[static_cast<size_t>(k / dwell) % stops.size()];
  return p;
}

// Per probe (x1, y1, x2, y2, z) its drift per K of head, column, bed and motor, mm/K.
inline const std::vector<std::vector<double>> kProbeDrift{
    {0.3e-3, 0.2e-3, 0, 0}, {1.5e-3, 2.5e-3, 0, 0}, {0.5e-3, 0.1e-3, 0, 0}, {1.9e-3, 2.6e-3, 0, 0}, {-1.2e-3, -0.8e-3, -1.5e-3, 0}};

// Seed 003's drift test every 30 s: probe sets at z = 50 and 150 mm; each probe from its own run
// of the machine (its own noise), the temperatures from the y1 probe's run.
inline DriftTestFile mahoDriftTest() {
  const auto loads = cycle({{6, 8}}, 120);
  DriftTestFile test;
  test.probes.z1 = 50;
  test.probes.z2 = 150;
  Eigen::VectorXd* probes[] = {&test.probes.x1, &test.probes.y1, &test.probes.x2, &test.probes.y2, &test.probes.z};
  for (size_t p = 0; p < 5; ++p) {
    const auto run = recordDriftTest(maho(20 + p, kProbeDrift[p]), loads, 30.0);
    *probes[p] = run.record.drift;
    if (p == 1) test.temperatures = run.record.temperatures;
  }
  test.time = Eigen::VectorXd::LinSpaced(loads.rows(), 0.0, 30.0 * static_cast<double>(loads.rows() - 1));
  test.spindleSpeed = 5000.0 * loads.col(0);
  test.sensors = {"room", "head", "column", "bed", "motor"};
  test.sensorLocations = {"1 m from the machine, 1.5 m high", "spindle head, front bearing", "column, top", "bed, centre", "spindle motor housing"};
  return test;
}

// ISO 230-3's environmental temperature variation test on the same machine: spindle at rest,
// the room swinging 1.5 K over the day, 26 h read every 60 s by x1, y1 and z.
inline DriftTestFile mahoEnvironmentTest() {
  const long samples = 26 * 60;
  const Eigen::MatrixXd loads = Eigen::MatrixXd::Zero(samples, 1);
  DriftTestFile test;
  Eigen::VectorXd* probes[] = {&test.probes.x1, &test.probes.y1, &test.probes.z};
  const size_t drifts[] = {0, 1, 4};
  for (size_t p = 0; p < 3; ++p) {
    auto machine = maho(40 + p, kProbeDrift[drifts[p]]);
    machine.roomSwing = 1.5;
    const auto run = recordDriftTest(machine, loads, 60.0);
    *probes[p] = run.record.drift;
    if (p == 1) test.temperatures = run.record.temperatures;
  }
  test.time = Eigen::VectorXd::LinSpaced(samples, 0.0, 60.0 * static_cast<double>(samples - 1));
  test.spindleSpeed = Eigen::VectorXd::Zero(samples);
  test.sensors = {"room", "head", "column", "bed", "motor"};
  test.sensorLocations = {"1 m from the machine, 1.5 m high", "spindle head, front bearing", "column, top", "bed, centre", "spindle motor housing"};
  return test;
}

// A Z-axis thermal drift test: Z traversing for 6 h (its drive and screw warming the nodes as the
// spindle did), then 8 h at rest, the mandrel read every 30 s with Z stopped at 0, -200 and
// -400 mm in turn for 10 min each. The Z probe's drift per K of the head grows by 5 nm/K per mm
// downwards (the screw's expansion between nut and bearing); y1's does not depend on Z.
inline DriftTestFile zAxisDriftTest() {
  const auto loads = cycle({{6, 8}}, 120);
  const Eigen::VectorXd z = stops(loads.rows(), {0, -200, -400}, 20);
  DriftTestFile test;
  Eigen::VectorXd* probes[] = {&test.probes.y1, &test.probes.z};
  for (size_t p = 0; p < 2; ++p) {
    auto machine = maho(60 + p, kProbeDrift[p == 0 ? 1 : 4]);
    if (p == 1) machine.driftGradient = {5e-6, 0, 0, 0};
    const auto run = recordDriftTest(machine, loads, 30.0, z);
    *probes[p] = run.record.drift;
    if (p == 0) test.temperatures = run.record.temperatures;
  }
  test.time = Eigen::VectorXd::LinSpaced(loads.rows(), 0.0, 30.0 * static_cast<double>(loads.rows() - 1));
  test.spindleSpeed = Eigen::VectorXd::Zero(loads.rows());
  test.axes = {"Z"};
  test.positions = z;
  test.sensors = {"room", "head", "column", "bed", "motor"};
  test.sensorLocations = {"1 m from the machine, 1.5 m high", "spindle head, front bearing", "column, top", "bed, centre", "spindle motor housing"};
  return test;
}

}  // namespace mtacc::test
