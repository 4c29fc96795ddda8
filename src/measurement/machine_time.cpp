#include "mtacc/measurement/machine_time.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

namespace mtacc {
namespace {

// A move of `distance` from rest to rest at most at `speed` (per s) and `acceleration` (per s^2).
double trapezoidSeconds(double distance, double speed, double acceleration) {
  if (distance <= 0) return 0.0;
  if (distance >= speed * speed / acceleration) return distance / speed + speed / acceleration;
  return 2.0 * std::sqrt(distance / acceleration);
}

bool staticReadings(Instrument instrument) { return instrument == Instrument::RTest || instrument == Instrument::TouchProbe; }

}  // namespace

double runMinutes(const Machine& m, const MeasurementRun& run, const MachineTimeModel& t) {
  const int n = m.commandedCount();
  double seconds = 0;
  for (Eigen::Index i = 1; i < run.poses(); ++i) {
    double move = 0, linearPath = 0;
    for (int j = 0; j < n; ++j) {
      const auto& axis = m.axes[static_cast<size_t>(j)];
      const double d = std::abs(run.q(i, j) - run.q(i - 1, j));
      const double speed = (axis.isRotary() ? t.rotaryRapid : t.linearRapid) / 60.0;
      if (!axis.isRotary()) linearPath += d * d;
      move = staticReadings(run.instrument)
                 ? std::max(move, trapezoidSeconds(d, speed, axis.isRotary() ? t.rotaryAcceleration : t.linearAcceleration))
                 : std::max(move, d / speed);
    }
    if (!staticReadings(run.instrument)) move = std::max(move, std::sqrt(linearPath) / (run.feed / 60.0));
    seconds += move;
  }
  if (run.instrument == Instrument::RTest) seconds += t.rtestDwell * static_cast<double>(run.poses());
  if (run.instrument == Instrument::TouchProbe) seconds += t.probeTime * static_cast<double>(run.poses());
  return seconds / 60.0;
}

std::string setupKey(const MeasurementRun& run) {
  if (!staticReadings(run.instrument)) return instrumentName(run.instrument) + " " + run.name;
  const auto tenth = [](double x) { return std::round(x * 10) / 10 + 0.0; };  // + 0.0: no "-0"
  const auto mm = [&](const Vec3& v) { return fmt::format("({:g}, {:g}, {:g}) mm", tenth(v.x()), tenth(v.y()), tenth(v.z())); };
  return fmt::format("{}: sphere at {}, tool ball {}", instrumentName(run.instrument), mm(run.setup.target), mm(run.setup.toolBall));
}

double planMinutes(const Machine& machine, const std::vector<MeasurementRun>& runs, const MachineTimeModel& time) {
  std::set<std::string> setups;
  std::set<Instrument> instruments;
  double minutes = 0;
  for (const auto& r : runs) {
    minutes += runMinutes(machine, r, time);
    setups.insert(setupKey(r));
    instruments.insert(r.instrument);
  }
  return minutes + time.setupMinutes * static_cast<double>(setups.size()) + time.instrumentMinutes * static_cast<double>(instruments.size());
}

}  // namespace mtacc
