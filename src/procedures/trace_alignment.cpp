#include "mtacc/procedures/trace_alignment.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mtacc {

namespace {

struct NormalisedChannel {
  UniformSpline command;
  const std::vector<double>* encoder;
  double inverseSpread;
};

// Mean squared normalised misfit over the encoder samples [first, last) with the command moved by `offset`.
double meanSquaredMisfit(const std::vector<NormalisedChannel>& channels, const SampledTrace& encoder, double offset,
                         size_t first, size_t last) {
  double sum = 0.0;
  for (const auto& channel : channels)
    for (size_t k = first; k < last; ++k) {
      const double t = encoder.start + encoder.period * static_cast<double>(k);
      const double misfit = ((*channel.encoder)[k] - channel.command(t - offset)) * channel.inverseSpread;
      sum += misfit * misfit;
    }
  return sum / static_cast<double>((last - first) * channels.size());
}

// The encoder samples whose time minus every offset in [lowest, highest] falls inside the command's span.
std::pair<size_t, size_t> comparedSamples(const SampledTrace& command, const SampledTrace& encoder, double lowest, double highest) {
  const double from = command.start + highest, to = command.end() + lowest;
  const auto n = static_cast<double>(encoder.samples());
  const double first = std::fmax(0.0, std::ceil((from - encoder.start) / encoder.period - 1e-9));
  const double last = std::fmin(n, std::floor((to - encoder.start) / encoder.period + 1e-9) + 1.0);
  if (!(last > first)) return {0, 0};
  return {static_cast<size_t>(first), static_cast<size_t>(last)};
}

std::vector<NormalisedChannel> normalisedChannels(const SampledTrace& command, const SampledTrace& encoder, Interpolation kind) {
  std::vector<NormalisedChannel> channels;
  for (size_t c = 0; c < encoder.channels.size(); ++c) {
    const auto& values = encoder.channels[c];
    double mean = 0.0, square = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (double v : values) square += (v - mean) * (v - mean);
    const double spread = std::sqrt(square / static_cast<double>(values.size()));
    if (!(spread > 1e-12 * (1.0 + std::fabs(mean)))) continue;
    channels.push_back({UniformSpline(command.start, command.period, command.channels[c], kind), &values, 1.0 / spread});
  }
  return channels;
}

}  // namespace

ClockOffset estimateClockOffset(const SampledTrace& command, const SampledTrace& encoder, const ClockOffsetSearch& search) {
  if (command.channels.size() != encoder.channels.size() || encoder.channels.empty())
    throw std::invalid_argument("clock offset: the command and encoder traces need the same channels");
  if (!(search.highest > search.lowest)) throw std::invalid_argument("clock offset: the search window is empty");
  const auto coarse = normalisedChannels(command, encoder, Interpolation::Linear);
  if (coarse.empty()) throw std::invalid_argument("clock offset: no axis moves in the encoder trace");
  const size_t enough = std::max<size_t>(4, encoder.samples() / 4);

  double best = std::numeric_limits<double>::quiet_NaN(), bestCost = std::numeric_limits<double>::infinity();
  const double step = std::fmax(encoder.period, (search.highest - search.lowest) / 20000);  // a bounded scan
  const auto steps = static_cast<long>(std::ceil((search.highest - search.lowest) / step));
  for (long i = 0; i <= steps; ++i) {
    const double offset = std::fmin(search.lowest + step * static_cast<double>(i), search.highest);
    const auto [first, last] = comparedSamples(command, encoder, offset, offset);
    if (last - first < enough) continue;
    const double cost = meanSquaredMisfit(coarse, encoder, offset, first, last);
    if (cost < bestCost) bestCost = cost, best = offset;
  }
  if (std::isnan(best))
    throw std::invalid_argument("clock offset: no offset in the search window overlaps a quarter of the encoder trace");

  const auto fine = normalisedChannels(command, encoder, search.interpolation);
  double lo = std::fmax(best - step, search.lowest), hi = std::fmin(best + step, search.highest);
  const auto [first, last] = comparedSamples(command, encoder, lo, hi);
  if (last - first < enough)
    throw std::invalid_argument("clock offset: the best offset leaves less than a quarter of the encoder trace to compare");
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
  double costA = meanSquaredMisfit(fine, encoder, a, first, last), costB = meanSquaredMisfit(fine, encoder, b, first, last);
  while (hi - lo > 1e-9) {
    if (costA < costB) {
      hi = b, b = a, costB = costA;
      a = hi - ratio * (hi - lo);
      costA = meanSquaredMisfit(fine, encoder, a, first, last);
    } else {
      lo = a, a = b, costA = costB;
      b = lo + ratio * (hi - lo);
      costB = meanSquaredMisfit(fine, encoder, b, first, last);
    }
  }
  const double offset = (lo + hi) / 2;
  return {offset, std::sqrt(meanSquaredMisfit(fine, encoder, offset, first, last)), last - first};
}

std::vector<std::vector<double>> resampleTrace(const SampledTrace& trace, double offset, const std::vector<double>& times,
                                               Interpolation interpolation) {
  std::vector<std::vector<double>> out;
  out.reserve(trace.channels.size());
  for (const auto& channel : trace.channels) {
    const UniformSpline spline(trace.start + offset, trace.period, channel, interpolation);
    auto& values = out.emplace_back(times.size());
    for (size_t i = 0; i < times.size(); ++i) values[i] = spline(times[i]);
  }
  return out;
}

}  // namespace mtacc
