#pragma once
// The position loop of one axis of the virtual machine (seed 004 §14.1): proportional gain Kv
// with velocity feed-forward k_ff, dx/dt = k_ff * dr/dt + Kv * (r - x). For a command moving at
// constant speed v the axis follows (1 - k_ff) * v / Kv behind, i.e. (1 - k_ff) / Kv in time.
#include <span>
#include <vector>

namespace mtacc {

struct ServoGains {
  double positionGain = 40.0;  // Kv, 1/s
  double feedForward = 1.0;    // k_ff, 0 .. 1
};

// The axis position at each command sample, the command being linear between samples `period`
// s apart and the axis at rest on the first sample. The loop is integrated exactly over each
// interval. Throws InvalidInput for a gain or period that is not positive and finite or
// a feed-forward outside [0, 1].
std::vector<double> followCommand(std::span<const double> command, double period, const ServoGains& gains);

}  // namespace mtacc
