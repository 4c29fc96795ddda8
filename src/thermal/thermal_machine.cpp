#include "mtacc/thermal/thermal_machine.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

ThermalRecording recordDriftTest(const VirtualThermalMachine& machine, const Eigen::MatrixXd& loads, double period,
                                 const Eigen::VectorXd& positions) {
  const size_t nodes = machine.nodes.size();
  if (machine.driftPerKelvin.size() != nodes)
    throw InvalidInput(fmt::format("{} drift coefficients for {} thermal nodes", machine.driftPerKelvin.size(), nodes));
  if (!machine.driftGradient.empty() && machine.driftGradient.size() != nodes)
    throw InvalidInput(fmt::format("{} drift gradients for {} thermal nodes", machine.driftGradient.size(), nodes));
  if (positions.size() && positions.size() != loads.rows())
    throw InvalidInput(fmt::format("{} positions for {} samples", positions.size(), loads.rows()));
  for (const int s : machine.sensedNode)
    if (s < -1 || s >= static_cast<int>(nodes)) throw InvalidInput(fmt::format("a sensor on node {} of {}", s, nodes));
  for (const auto& node : machine.nodes) {
    if (!(node.timeConstant > 0)) throw InvalidInput("a thermal node's time constant must be positive");
    if (static_cast<long>(node.heatGains.size()) != loads.cols())
      throw InvalidInput(fmt::format("a thermal node with {} heat gains for {} loads", node.heatGains.size(), loads.cols()));
  }
  if (!(period > 0)) throw InvalidInput("the sampling period must be positive");

  const long n = loads.rows();
  ThermalRecording out;
  out.nodes.resize(n, static_cast<long>(nodes));
  out.trueDrift.resize(n);
  Eigen::VectorXd rooms(n);
  std::vector<double> temperature(nodes, machine.room);
  for (long k = 0; k < n; ++k) {
    const double room = machine.room + machine.roomSwing * std::sin(2 * std::numbers::pi * static_cast<double>(k) * period / 86400.0);
    rooms[k] = room;
    double drift = 0.0;
    const double position = positions.size() ? positions[k] : 0.0;
    for (size_t j = 0; j < nodes; ++j) {
      out.nodes(k, static_cast<long>(j)) = temperature[j];
      const double gradient = machine.driftGradient.empty() ? 0.0 : machine.driftGradient[j];
      drift += (machine.driftPerKelvin[j] + gradient * position) * (temperature[j] - machine.room);
      const double settle = std::exp(-period / machine.nodes[j].timeConstant);
      double target = room;
      for (long l = 0; l < loads.cols(); ++l) target += machine.nodes[j].heatGains[static_cast<size_t>(l)] * loads(k, l);
      temperature[j] = target + (temperature[j] - target) * settle;
    }
    out.trueDrift[k] = drift;
  }
  std::mt19937_64 random(machine.seed);
  std::normal_distribution<double> sensorNoise(0.0, machine.sensorNoise), driftNoise(0.0, machine.driftNoise);
  out.record.temperatures.resize(n, static_cast<long>(machine.sensedNode.size()));
  out.record.drift.resize(n);
  out.record.position = positions;
  for (long k = 0; k < n; ++k) {
    for (size_t s = 0; s < machine.sensedNode.size(); ++s) {
      const int node = machine.sensedNode[s];
      out.record.temperatures(k, static_cast<long>(s)) = (node < 0 ? rooms[k] : out.nodes(k, node)) + sensorNoise(random);
    }
    out.record.drift[k] = out.trueDrift[k] + driftNoise(random);
  }
  return out;
}

}  // namespace mtacc
