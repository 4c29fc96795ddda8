#pragma once
// A virtual machine that warms and cools: first-order thermal nodes driven by heat loads (the
// spindle, the axes' motion) and by the room, temperature sensors on some nodes and in the room, and one drift
// component that is a known linear function of the nodes' temperatures. It records drift tests
// such as seed 003's (5000 rpm for 6 h, then 8 h at rest) from a known truth.
#include <cstdint>
#include <vector>

#include "mtacc/thermal/drift_regression.hpp"

namespace mtacc {

struct ThermalNode {
  double timeConstant = 3600.0;    // s
  std::vector<double> heatGains;   // per heat load: K of steady-state rise per unit of that load
};

struct VirtualThermalMachine {
  std::vector<ThermalNode> nodes;
  std::vector<double> driftPerKelvin;  // per node, mm/K: the drift is sum_j (d_j + g_j p) (T_j - T_j(0)) at axis position p
  std::vector<double> driftGradient;   // per node, g_j in mm/K per mm; empty: the drift does not depend on the position
  std::vector<int> sensedNode;         // per sensor, the node it measures; -1: the room
  double room = 20.0;                  // degC at the start; every node starts at it
  double roomSwing = 0.0;              // K: amplitude of the room's daily sine
  double sensorNoise = 0.02;           // K, standard deviation
  double driftNoise = 0.3e-3;          // mm, standard deviation
  std::uint64_t seed = 1;
};

// One sample per row of `loads` (samples x heat loads, e.g. the spindle speed over its top
// speed), `period` s apart, each load held over its period and the nodes following exactly
// (first order, each also towards the room), the drift read where the axis stands (`positions`,
// mm, one per sample; empty: at 0). Also returns the true drift and node temperatures,
// noise-free. Throws InvalidInput for a machine whose lists do not match, a node of
// non-positive time constant, a period that is not positive, or positions not one per sample.
struct ThermalRecording {
  ThermalRecord record;       // the sensors and the measured drift (with noise)
  Eigen::MatrixXd nodes;      // samples x nodes, degC, noise-free
  Eigen::VectorXd trueDrift;  // mm, noise-free
};
ThermalRecording recordDriftTest(const VirtualThermalMachine& machine, const Eigen::MatrixXd& loads, double period,
                                 const Eigen::VectorXd& positions = {});

}  // namespace mtacc
