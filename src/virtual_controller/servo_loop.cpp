#include "mtacc/virtual_controller/servo_loop.hpp"

#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::vector<double> followCommand(std::span<const double> command, double period, const ServoGains& gains) {
  if (!(gains.positionGain > 0.0) || !std::isfinite(gains.positionGain))
    throw InvalidInput("servo loop: the position gain must be positive and finite");
  if (!(gains.feedForward >= 0.0 && gains.feedForward <= 1.0))
    throw InvalidInput("servo loop: the feed-forward must lie in [0, 1]");
  if (!(period > 0.0) || !std::isfinite(period)) throw InvalidInput("servo loop: the period must be positive and finite");
  std::vector<double> axis(command.size());
  if (command.empty()) return axis;
  // The following error e = r - x obeys de/dt = (1 - k_ff) v - Kv e for a command speed v.
  const double decay = std::exp(-gains.positionGain * period);
  const double lagPerSpeed = (1.0 - gains.feedForward) / gains.positionGain;
  double following = 0.0;
  axis[0] = command[0];
  for (size_t k = 1; k < command.size(); ++k) {
    const double speed = (command[k] - command[k - 1]) / period;
    following = following * decay + lagPerSpeed * speed * (1.0 - decay);
    axis[k] = command[k] - following;
  }
  return axis;
}

}  // namespace mtacc
