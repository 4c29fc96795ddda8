#include "mtacc/compensation/rotary_positioning.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

constexpr double kSpacing = 2.0 * std::numbers::pi / 180.0;  // rad: at most this between the positions,
constexpr int kMostIntervals = 255;                            // unless that makes more than LinuxCNC's 256 lines

// The correction of axis k's command at q, the axis moving `direction` (0 standing): the turn of
// the machine with its errors about the nominal turn's axis, negated, over that turn's rate.
double ownCorrection(const KinematicModel& actual, const KinematicModel& nominal, std::vector<double> q, size_t k, int direction) {
  constexpr double h = 1e-6;  // rad
  std::vector<int> dir(q.size(), 0);
  dir[k] = direction;
  const Pose wanted = toolInWorkpiece(nominal, q.data());
  const Vec3 turn = poseError(toolInWorkpiece(actual, q.data(), dir.data()), wanted).tail<3>();
  q[k] += h;
  const Vec3 rate = poseError(toolInWorkpiece(nominal, q.data()), wanted).tail<3>() / h;
  return -turn.dot(rate) / rate.squaredNorm();
}

}  // namespace

double RotaryPositioning::correction(double position) const {
  const double first = positions.front(), step = positions.size() > 1 ? positions[1] - first : 1.0;
  double u = (position - first) / step;
  const auto last = static_cast<double>(positions.size() - 1);
  if (modulo) u = std::fmod(std::fmod(u, last) + last, last);
  u = std::clamp(u, 0.0, last);
  const auto n = std::min(static_cast<size_t>(u), positions.size() - 2);
  const double t = u - static_cast<double>(n);
  return (1.0 - t) * standing[n] + t * standing[n + 1];
}

std::vector<RotaryPositioning> rotaryPositioning(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors,
                                                 const std::vector<double>& pose) {
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  std::vector<RotaryPositioning> out;
  for (int k = 0; k < machine->commandedCount(); ++k) {
    const Axis& axis = machine->axes[static_cast<size_t>(k)];
    if (!axis.isRotary()) continue;
    RotaryPositioning r;
    r.axis = k;
    r.modulo = !axis.travel;
    const double low = axis.travel ? axis.travel->min : 0.0, high = axis.travel ? axis.travel->max : 2.0 * std::numbers::pi;
    const int intervals = std::clamp(static_cast<int>(std::ceil((high - low) / kSpacing - 1e-9)), 1, kMostIntervals);
    std::vector<double> q = pose;
    for (int n = 0; n <= intervals; ++n) {
      q[static_cast<size_t>(k)] = low + (high - low) * n / intervals;
      r.positions.push_back(q[static_cast<size_t>(k)]);
      r.standing.push_back(ownCorrection(actual, nominal, q, static_cast<size_t>(k), 0));
      r.forward.push_back(ownCorrection(actual, nominal, q, static_cast<size_t>(k), 1));
      r.reverse.push_back(ownCorrection(actual, nominal, q, static_cast<size_t>(k), -1));
    }
    // A model that does not repeat over the turn (a polynomial in the angle) cannot be a modulo table.
    r.modulo = r.modulo && std::abs(r.standing.front() - r.standing.back()) < 1e-12 &&
               std::abs(r.forward.front() - r.forward.back()) < 1e-12 && std::abs(r.reverse.front() - r.reverse.back()) < 1e-12;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace mtacc
