#include "mtacc/procedures/trace_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

namespace {

// The command's moving channels as splines (one start, period and length: they share each
// location), each with its encoder samples and the inverse of their spread.
struct NormalisedChannels {
  std::vector<UniformSpline> command;
  std::vector<const std::vector<double>*> encoder;
  std::vector<double> inverseSpread;
};

NormalisedChannels normalisedChannels(const SampledTrace& command, const SampledTrace& encoder, Interpolation kind) {
  NormalisedChannels channels;
  for (size_t c = 0; c < encoder.channels.size(); ++c) {
    const auto& values = encoder.channels[c];
    double mean = 0.0, square = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (double v : values) square += (v - mean) * (v - mean);
    const double spread = std::sqrt(square / static_cast<double>(values.size()));
    if (!(spread > 1e-12 * (1.0 + std::fabs(mean)))) continue;
    channels.command.emplace_back(command.start, command.period, command.channels[c], kind);
    channels.encoder.push_back(&values);
    channels.inverseSpread.push_back(1.0 / spread);
  }
  return channels;
}

// Over the encoder samples [first, last) with the command moved by `offset`: the mean squared
// normalised misfit, and (with `gauss`) the sums of residual * slope and slope^2 of the misfit
// in the offset, for a Gauss-Newton step. A channel at a time, the command evaluated at all the
// samples' times at once.
struct Misfit {
  double meanSquare = 0.0, residualSlope = 0.0, slopeSquare = 0.0;
};
Misfit misfit(const NormalisedChannels& channels, const SampledTrace& encoder, double offset, size_t first, size_t last, bool gauss) {
  Misfit m;
  const size_t count = last - first;
  const auto rows = static_cast<Eigen::Index>(count);
  const double firstTime = encoder.start + encoder.period * static_cast<double>(first) - offset;
  Eigen::VectorXd residual(rows), slope(gauss ? rows : 0);
  for (size_t c = 0; c < channels.command.size(); ++c) {
    const double scale = channels.inverseSpread[c];
    channels.command[c].atEvenly(firstTime, encoder.period, {residual.data(), count});
    residual = (Eigen::Map<const Eigen::VectorXd>(channels.encoder[c]->data() + first, rows) - residual) * scale;
    m.meanSquare += residual.squaredNorm();
    if (!gauss) continue;
    channels.command[c].slopeAtEvenly(firstTime, encoder.period, {slope.data(), count});
    slope *= scale;  // d residual / d offset
    m.residualSlope += residual.dot(slope);
    m.slopeSquare += slope.squaredNorm();
  }
  m.meanSquare /= static_cast<double>(count * channels.command.size());
  return m;
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

}  // namespace

ClockOffset estimateClockOffset(const SampledTrace& command, const SampledTrace& encoder, const ClockOffsetSearch& search) {
  if (command.channels.size() != encoder.channels.size() || encoder.channels.empty())
    throw InvalidInput("clock offset: the command and encoder traces need the same channels");
  if (!(search.highest > search.lowest)) throw InvalidInput("clock offset: the search window is empty");
  const auto coarse = normalisedChannels(command, encoder, Interpolation::Linear);
  if (coarse.command.empty()) throw InvalidInput("clock offset: no axis moves in the encoder trace");
  const size_t enough = std::max<size_t>(4, encoder.samples() / 4);

  double best = std::numeric_limits<double>::quiet_NaN(), bestCost = std::numeric_limits<double>::infinity();
  const double step = std::fmax(encoder.period, (search.highest - search.lowest) / 20000);  // a bounded scan
  const auto steps = static_cast<long>(std::ceil((search.highest - search.lowest) / step));
  for (long i = 0; i <= steps; ++i) {
    const double offset = std::fmin(search.lowest + step * static_cast<double>(i), search.highest);
    const auto [first, last] = comparedSamples(command, encoder, offset, offset);
    if (last - first < enough) continue;
    const double cost = misfit(coarse, encoder, offset, first, last, false).meanSquare;
    if (cost < bestCost) bestCost = cost, best = offset;
  }
  if (std::isnan(best))
    throw InvalidInput("clock offset: no offset in the search window overlaps a quarter of the encoder trace");

  // Gauss-Newton on the interpolated traces within one scan step of the best offset, halving a
  // step that does not lower the misfit; the minimum of a smooth misfit is found to rounding.
  const auto fine = normalisedChannels(command, encoder, search.interpolation);
  const double lo = std::fmax(best - step, search.lowest), hi = std::fmin(best + step, search.highest);
  const auto [first, last] = comparedSamples(command, encoder, lo, hi);
  if (last - first < enough)
    throw InvalidInput("clock offset: the best offset leaves less than a quarter of the encoder trace to compare");
  double offset = best;
  Misfit current = misfit(fine, encoder, offset, first, last, true);
  for (int iteration = 0; iteration < 50 && current.slopeSquare > 0; ++iteration) {
    double change = -current.residualSlope / current.slopeSquare, trial = offset;
    Misfit next;
    int halving = 0;
    for (; halving < 30; ++halving, change /= 2) {
      trial = std::fmin(std::fmax(offset + change, lo), hi);
      next = misfit(fine, encoder, trial, first, last, true);
      if (next.meanSquare <= current.meanSquare) break;
    }
    if (halving == 30) break;
    const double moved = std::fabs(trial - offset);
    offset = trial;
    current = next;
    if (moved < 1e-13) break;
  }
  return {offset, std::sqrt(current.meanSquare), last - first};
}

JointMatrix resampleTrace(const SampledTrace& trace, double offset, const EvenTimes& times, Interpolation interpolation) {
  JointMatrix out(static_cast<Eigen::Index>(times.count), static_cast<Eigen::Index>(trace.channels.size()));
  resampleTrace(trace, offset, times, out, interpolation);
  return out;
}

void resampleTrace(const SampledTrace& trace, double offset, const EvenTimes& times, Eigen::Ref<JointMatrix> out,
                   Interpolation interpolation) {
  if (out.rows() != static_cast<Eigen::Index>(times.count) || out.cols() != static_cast<Eigen::Index>(trace.channels.size()))
    throw std::logic_error("resampleTrace: the output is not one row per time and one column per channel");
  // A block of times a channel at a time: each channel's spline evaluated in one vectorised pass
  // into a buffer that stays in the cache, then into the output's column.
  constexpr size_t kBlock = 4096;
  std::vector<double> buffer(std::min(kBlock, times.count));
  for (size_t c = 0; c < trace.channels.size(); ++c) {
    const UniformSpline spline(trace.start + offset, trace.period, trace.channels[c], interpolation);
    for (size_t b = 0; b < times.count; b += kBlock) {
      const size_t length = std::min(kBlock, times.count - b);
      spline.atEvenly(times.first + times.step * static_cast<double>(b), times.step, {buffer.data(), length});
      for (size_t k = 0; k < length; ++k) out(static_cast<Eigen::Index>(b + k), static_cast<Eigen::Index>(c)) = buffer[k];
    }
  }
}

}  // namespace mtacc
