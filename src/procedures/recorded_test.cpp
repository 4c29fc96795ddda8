#include "mtacc/procedures/recorded_test.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/procedures/signal_spikes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

namespace {

// The command's last sample at its first values and its first sample at its last values: the
// motion between them is the test (seed 004 O5: normalised time from the first point to the last).
std::pair<double, double> motionSpan(const SampledTrace& command) {
  const size_t n = command.samples();
  size_t departure = n - 1, arrival = 0;
  for (const auto& channel : command.channels) {
    const auto [low, high] = std::minmax_element(channel.begin(), channel.end());
    const double still = 1e-9 * (*high - *low) + 1e-12;
    size_t first = 0, last = n - 1;
    while (first + 1 < n && std::fabs(channel[first + 1] - channel.front()) <= still) ++first;
    while (last > 0 && std::fabs(channel[last - 1] - channel.back()) <= still) --last;
    departure = std::min(departure, first);
    arrival = std::max(arrival, last);
  }
  if (arrival <= departure) return {command.start, command.end()};  // nothing moves: the whole trace
  return {command.start + command.period * static_cast<double>(departure), command.start + command.period * static_cast<double>(arrival)};
}

// The norm over the axes of their acceleration (file units: mm and deg per s^2), by central
// differences on the trace's own samples, interpolated linearly at the given times.
LargeVector<double> axisAcceleration(const SampledTrace& trace, const std::vector<double>& fileScale, std::span<const double> times) {
  const size_t m = trace.samples();
  std::vector<double> square(m, 0.0);
  for (size_t a = 0; a < trace.channels.size(); ++a) {
    const auto& x = trace.channels[a];
    for (size_t k = 1; k + 1 < m; ++k) {
      const double second = (x[k + 1] - 2.0 * x[k] + x[k - 1]) / (trace.period * trace.period) * fileScale[a];
      square[k] += second * second;
    }
  }
  if (m >= 3) {
    square.front() = square[1];
    square.back() = square[m - 2];
  }
  LargeVector<double> out;
  out.reserve(times.size());
  for (const double t : times) {
    const double at = std::clamp((t - trace.start) / trace.period, 0.0, static_cast<double>(m - 1));
    const auto k = std::min(static_cast<size_t>(at), m >= 2 ? m - 2 : 0);
    const double w = at - static_cast<double>(k);
    out.push_back(std::sqrt(m >= 2 ? (1.0 - w) * square[k] + w * square[k + 1] : square[0]));
  }
  return out;
}

}  // namespace

AlignedTest alignRecordedTest(const KinematicModel& nominal, const KinematicModel& identified, const RecordedSignals& signals,
                              const SignalProcessing& processing, int threads) {
  const auto& [feed, command, encoder, instrument] = signals;
  AlignedTest out;
  auto& alignment = out.alignment;
  if (processing.clockOffset) {
    alignment.offset = *processing.clockOffset;
    try {
      alignment.tracesOffset = estimateClockOffset(command, encoder, processing.search).offset;
    } catch (const InvalidInput&) {
      // The stated offset is used as given; the traces cannot say whether it is right.
    }
  } else {
    const auto found = estimateClockOffset(command, encoder, processing.search);
    alignment.offset = found.offset;
    alignment.estimated = true;
    alignment.rmsMisfit = found.rmsMisfit;
    const double step = std::fmax(encoder.period, (processing.search.highest - processing.search.lowest) / 20000);
    alignment.atSearchLimit = found.offset - processing.search.lowest < step || processing.search.highest - found.offset < step;
  }
  alignment.instrumentSamples = instrument.samples();
  alignment.instrumentSpikes = spikeSamples(instrument);
  const auto [departure, arrival] = motionSpan(command);
  const double from = std::max(departure + alignment.offset, encoder.start);
  const double to = std::min(arrival + alignment.offset, encoder.end());
  auto& test = out.test;
  test.feed = feed;
  // The instrument's samples in [from, to]: one contiguous run.
  size_t first = instrument.samples(), n = 0;
  for (size_t j = 0; j < instrument.samples(); ++j) {
    const double t = instrument.start + instrument.period * static_cast<double>(j);
    if (t >= from && t <= to) first = std::min(first, j), n = j - first + 1;
  }
  alignment.samplesUsed = n;
  alignment.firstSampleUsed = n == 0 ? 0 : first;
  if (n < 4)
    throw InvalidInput(fmt::format("{} instrument samples fall inside the command's motion and the encoder trace (offset {:.3f} ms)",
                                            n, alignment.offset * 1e3));
  test.time.resize(n);
  for (size_t i = 0; i < n; ++i) test.time[i] = instrument.start + instrument.period * static_cast<double>(first + i);
  const auto interpolation = processing.search.interpolation;
  const auto axes = static_cast<Eigen::Index>(command.channels.size());
  LargeJointMatrix nominalPoses(static_cast<Eigen::Index>(n), axes);
  out.encoderPoses = LargeJointMatrix(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(encoder.channels.size()));
  auto nominalQ = nominalPoses.matrix();
  auto encoderQ = out.encoderPoses.matrix();
  const EvenTimes times{test.time.front(), instrument.period, n};
  resampleTrace(command, alignment.offset, times, nominalQ, interpolation);
  resampleTrace(encoder, 0.0, times, encoderQ, interpolation);
  std::vector<double> fileScale;  // FGROUP: the path in mm and deg
  for (long a = 0; a < encoderQ.cols(); ++a) fileScale.push_back(1.0 / nominal.machine->axes[static_cast<size_t>(a)].fileUnit());
  test.acceleration = axisAcceleration(encoder, fileScale, test.time);
  test.path.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) {
    double square = 0.0;
    for (long a = 0; a < encoderQ.cols(); ++a) {
      const double step = (encoderQ(static_cast<long>(i), a) - encoderQ(static_cast<long>(i) - 1, a)) * fileScale[static_cast<size_t>(a)];
      square += step * step;
    }
    test.path[i] = test.path[i - 1] + std::sqrt(square);
  }
  test.nominal.resize(n);
  test.encoder.resize(n);
  test.link.resize(n);
  test.measured.resize(n);
  test.workpieceRotation.resize(n);
  // The TCPs and the workpiece's rotation sample by sample, straight into the test's series.
  parallelFor(static_cast<long>(n), threads, [&](long begin, long end) {
    for (long k = begin; k < end; ++k) {
      const auto i = static_cast<size_t>(k);
      const double* q = encoderQ.row(k).data();
      const auto [atEncoder, workpieceRotation] = toolPositionAndWorkpieceRotation(nominal, q);
      test.workpieceRotation[i] = workpieceRotation;
      test.nominal[i] = toolPosition(nominal, nominalQ.row(k).data()) - processing.ball;
      test.encoder[i] = atEncoder - processing.ball;
      test.link[i] = toolPosition(identified, q) - atEncoder;
    }
  });
  for (size_t i = 0; i < n; ++i)
    test.measured[i] = Vec3(instrument.channels[0][first + i], instrument.channels[1][first + i], instrument.channels[2][first + i]);
  return out;
}

}  // namespace mtacc
