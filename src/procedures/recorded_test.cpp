#include "mtacc/procedures/recorded_test.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

AlignedTest alignRecordedTest(const KinematicModel& nominal, const KinematicModel& identified, const RecordedSignals& signals,
                              const SignalProcessing& processing, int threads) {
  const auto& [feed, command, encoder, instrument] = signals;
  AlignedTest out;
  auto& alignment = out.alignment;
  if (processing.clockOffset) {
    alignment.offset = *processing.clockOffset;
  } else {
    const auto found = estimateClockOffset(command, encoder, processing.search);
    alignment = {found.offset, true, found.rmsMisfit, 0, 0};
  }
  alignment.instrumentSamples = instrument.samples();
  const double from = std::max(command.start + alignment.offset, encoder.start);
  const double to = std::min(command.end() + alignment.offset, encoder.end());
  auto& test = out.test;
  test.feed = feed;
  std::vector<size_t> used;
  for (size_t j = 0; j < instrument.samples(); ++j) {
    const double t = instrument.start + instrument.period * static_cast<double>(j);
    if (t >= from && t <= to) {
      test.time.push_back(t);
      used.push_back(j);
    }
  }
  alignment.samplesUsed = used.size();
  if (used.size() < 4)
    throw std::invalid_argument(fmt::format("{} instrument samples fall inside the command and encoder traces (offset {:.3f} ms)",
                                            used.size(), alignment.offset * 1e3));
  const auto interpolation = processing.search.interpolation;
  const auto nominalQ = posesFromChannels(resampleTrace(command, alignment.offset, test.time, interpolation));
  const auto encoderQ = posesFromChannels(resampleTrace(encoder, 0.0, test.time, interpolation));
  const PointMatrix atCommand = toolPositions(nominal, nominalQ, threads), atEncoder = toolPositions(nominal, encoderQ, threads);
  const PointMatrix withErrors = toolPositions(identified, encoderQ, threads);
  const size_t n = used.size();
  test.nominal.resize(n);
  test.encoder.resize(n);
  test.link.resize(n);
  test.measured.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto k = static_cast<long>(i);
    test.nominal[i] = atCommand.row(k).transpose() - processing.ball;
    test.encoder[i] = atEncoder.row(k).transpose() - processing.ball;
    test.link[i] = (withErrors.row(k) - atEncoder.row(k)).transpose();
    test.measured[i] = Vec3(instrument.channels[0][used[i]], instrument.channels[1][used[i]], instrument.channels[2][used[i]]);
  }
  return out;
}

}  // namespace mtacc
