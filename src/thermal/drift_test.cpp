#include "mtacc/thermal/drift_test.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

const char* nameOf(DriftDirection direction) {
  constexpr const char* names[] = {"X", "Y", "Z", "A", "B"};
  return names[static_cast<int>(direction)];
}

MandrelDrift mandrelDrift(const MandrelProbes& p) {
  long n = -1;
  for (const auto* probe : {&p.x1, &p.y1, &p.x2, &p.y2, &p.z}) {
    if (probe->size() == 0) continue;
    if (n >= 0 && probe->size() != n) throw InvalidInput(fmt::format("probe readings of {} and {} samples", n, probe->size()));
    n = probe->size();
  }
  if (n < 0) throw InvalidInput("no probe readings");
  const auto fromStart = [](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v.array() - v[0]; };
  MandrelDrift d;
  const auto set = [&](DriftDirection direction, const Eigen::VectorXd& v) { d.series[static_cast<int>(direction)] = v; };
  if (p.x1.size()) set(DriftDirection::X, fromStart(p.x1));
  if (p.y1.size()) set(DriftDirection::Y, fromStart(p.y1));
  if (p.z.size()) set(DriftDirection::Z, fromStart(p.z));
  const bool tilts = (p.x1.size() && p.x2.size()) || (p.y1.size() && p.y2.size());
  if (tilts && !(std::fabs(p.z2 - p.z1) > 1e-9))
    throw InvalidInput(fmt::format("the probe sets sit at one height ({} mm): no tilt", p.z1));
  const double arm = p.z2 - p.z1;
  if (p.y1.size() && p.y2.size()) set(DriftDirection::A, -(fromStart(p.y2) - fromStart(p.y1)) / arm);
  if (p.x1.size() && p.x2.size()) set(DriftDirection::B, (fromStart(p.x2) - fromStart(p.x1)) / arm);
  return d;
}

DriftExtremes driftExtremes(const Eigen::VectorXd& drift, const Eigen::VectorXd& time) {
  DriftExtremes e;
  Eigen::Index at = 0;
  drift.cwiseAbs().maxCoeff(&at);
  e.largest = drift[at];
  e.time = time[at];
  e.range = drift.maxCoeff() - drift.minCoeff();
  return e;
}

std::optional<DriftHysteresis> driftHysteresis(const Eigen::VectorXd& drift, const Eigen::VectorXd& temperature, int bins) {
  const long n = temperature.size();
  if (drift.size() != n) throw InvalidInput(fmt::format("{} drift samples for {} temperatures", drift.size(), n));
  if (bins < 1) throw InvalidInput("at least one temperature bin");
  Eigen::Index peak = 0;
  temperature.maxCoeff(&peak);
  if (peak == 0 || peak == n - 1) return std::nullopt;
  const auto warm = temperature.head(peak + 1), cool = temperature.tail(n - peak - 1);
  DriftHysteresis h;
  h.bins = bins;
  h.commonLow = std::max(warm.minCoeff(), cool.minCoeff());
  h.commonHigh = std::min(warm.maxCoeff(), cool.maxCoeff());
  if (!(h.commonHigh > h.commonLow)) return std::nullopt;
  const double width = (h.commonHigh - h.commonLow) / bins;
  std::vector<double> sum[2] = {std::vector<double>(static_cast<size_t>(bins)), std::vector<double>(static_cast<size_t>(bins))};
  std::vector<int> count[2] = {std::vector<int>(static_cast<size_t>(bins)), std::vector<int>(static_cast<size_t>(bins))};
  for (long k = 0; k < n; ++k) {
    const double t = temperature[k];
    if (t < h.commonLow || t > h.commonHigh) continue;
    const auto bin = static_cast<size_t>(std::min<long>(bins - 1, static_cast<long>((t - h.commonLow) / width)));
    const int branch = k <= peak ? 0 : 1;
    sum[branch][bin] += drift[k];
    ++count[branch][bin];
  }
  bool any = false;
  for (size_t b = 0; b < static_cast<size_t>(bins); ++b) {
    if (count[0][b] == 0 || count[1][b] == 0) continue;
    const double difference = sum[1][b] / count[1][b] - sum[0][b] / count[0][b];
    if (!any || std::fabs(difference) > std::fabs(h.difference)) {
      h.difference = difference;
      h.temperature = h.commonLow + (static_cast<double>(b) + 0.5) * width;
      any = true;
    }
  }
  return any ? std::optional(h) : std::nullopt;
}

}  // namespace mtacc
