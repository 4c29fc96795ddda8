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

}  // namespace mtacc::test
