// Seed 004 (L133, L284-290; extraction §4, O1, O7): the command trace, recorded in a run of its
// own, moved onto the encoder clock. V5 of the extraction's §14.4 on a five-axis motion followed
// by the servo loops of §14.1 (own amplitudes and clock offset), and R8.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/virtual_controller/servo_loop.hpp"
#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {
namespace {

constexpr double kNcPeriod = 0.003;  // s (L290)
constexpr int kFineSteps = 12;       // servo integration steps per NC period

// Five axes (X, Y, Z in mm, A, C in deg) moving smoothly and not periodically for 6 s.
double reference(int axis, double t) {
  constexpr double amplitude[] = {80, 45, 30, 20, 60}, pulsation[] = {1.1, 1.7, 2.3, 0.9, 1.3};
  constexpr double phase[] = {0.2, 1.0, -0.7, 0.4, 2.0}, bow[] = {1.5, -2.0, 0.8, 0.6, -1.2};
  return amplitude[axis] * std::sin(pulsation[axis] * t + phase[axis]) + bow[axis] * (t - 3.0) * (t - 3.0);
}

struct Recording {
  SampledTrace command, encoder;
};

// The command stamped s holds the reference at encoder time s + clockOffset (the command clock
// is behind); the encoder is the servo loop's output sampled every NC period.
Recording record(double clockOffset, const ServoGains (&gains)[5]) {
  const int samples = 2000;
  Recording r;
  r.command = {0.0, kNcPeriod, {}};
  r.encoder = {0.0, kNcPeriod, {}};
  for (int axis = 0; axis < 5; ++axis) {
    auto& command = r.command.channels.emplace_back(samples);
    for (int k = 0; k < samples; ++k) command[k] = reference(axis, k * kNcPeriod + clockOffset);
    std::vector<double> fine(samples * kFineSteps);
    for (size_t j = 0; j < fine.size(); ++j) fine[j] = reference(axis, static_cast<double>(j) * kNcPeriod / kFineSteps);
    const auto followed = followCommand(fine, kNcPeriod / kFineSteps, gains[axis]);
    auto& encoder = r.encoder.channels.emplace_back(samples);
    for (int k = 0; k < samples; ++k) encoder[k] = followed[static_cast<size_t>(k) * kFineSteps];
  }
  return r;
}

constexpr double kOffset = 0.0173;  // s, not a whole number of NC periods

TEST(Seed004Alignment, V5WithoutServoLagTheEstimatedShiftIsTheClockOffset) {
  const ServoGains exact[5] = {{40, 1}, {45, 1}, {50, 1}, {35, 1}, {30, 1}};
  const auto r = record(kOffset, exact);
  const auto found = estimateClockOffset(r.command, r.encoder);
  EXPECT_NEAR(found.offset, kOffset, 1e-4);  // V5: +-0.1 ms
  EXPECT_NEAR(found.offset, kOffset, 1e-7) << "the cubic spline of a 3 ms trace of this motion is good to far better";
  EXPECT_LT(found.rmsMisfit, 1e-6);
  EXPECT_GT(found.samplesCompared, 1900u);
}

// With k_ff = 0.99 each axis lags (1 - k_ff) / Kv = 0.20 .. 0.33 ms behind its command: the best
// delay absorbs a blend of these lags, so the estimate moves from the clock offset by that much.
TEST(Seed004Alignment, V5WithServoLagTheEstimateIsTheOffsetPlusTheEffectiveLag) {
  const ServoGains lagging[5] = {{40, 0.99}, {45, 0.99}, {50, 0.99}, {35, 0.99}, {30, 0.99}};
  const auto r = record(kOffset, lagging);
  const auto found = estimateClockOffset(r.command, r.encoder);
  EXPECT_NEAR(found.offset, kOffset, 5e-4);  // V5: +-0.5 ms with lag
  EXPECT_GE(found.offset - kOffset, 0.01 / 50 - 1e-5);
  EXPECT_LE(found.offset - kOffset, 0.01 / 30 + 1e-5);
}

TEST(Seed004Alignment, LinearInterpolationFindsTheOffsetLessClosely) {
  const ServoGains exact[5] = {{40, 1}, {45, 1}, {50, 1}, {35, 1}, {30, 1}};
  const auto r = record(kOffset, exact);
  const auto linear = estimateClockOffset(r.command, r.encoder, {.interpolation = Interpolation::Linear});
  const auto cubic = estimateClockOffset(r.command, r.encoder);
  EXPECT_NEAR(linear.offset, kOffset, 1e-4);
  EXPECT_GT(linear.rmsMisfit, 10 * cubic.rmsMisfit);
}

TEST(Seed004Alignment, ServoLoopFollowsARampByTheFeedForwardLag) {
  std::vector<double> ramp(3000);
  for (size_t k = 0; k < ramp.size(); ++k) ramp[k] = 100.0 * static_cast<double>(k) * 1e-3;  // 100 mm/s
  const auto axis = followCommand(ramp, 1e-3, {.positionGain = 40, .feedForward = 0.99});
  EXPECT_NEAR(ramp.back() - axis.back(), 100.0 * 0.01 / 40, 1e-12);  // steady following error, mm
  EXPECT_EQ(axis.front(), ramp.front());
  EXPECT_THROW(followCommand(ramp, 1e-3, {.positionGain = 0}), InvalidInput);
  EXPECT_THROW(followCommand(ramp, 1e-3, {.positionGain = 40, .feedForward = 1.5}), InvalidInput);
  EXPECT_THROW(followCommand(ramp, 0.0, {}), InvalidInput);
}

// R8 (L133, L290): moved by 18 ms onto the 10 kHz instrument clock, the 3 ms command trace's
// sample k lands on instrument sample 180 + 30 k: 18 ms is 6 NC cycles and 180 CapBall samples.
TEST(Seed004Alignment, R8EighteenMillisecondsAreSixNcCyclesAnd180InstrumentSamples) {
  SampledTrace command{0.0, kNcPeriod, {std::vector<double>(400)}};
  for (size_t k = 0; k < 400; ++k) command.channels[0][k] = std::sin(0.05 * static_cast<double>(k * k % 97));
  const double instrumentPeriod = 1e-4, delay = 0.018;
  const auto moved = resampleTrace(command, delay, EvenTimes{180 * instrumentPeriod, instrumentPeriod, 30 * 399 + 1});
  for (size_t k = 0; k < 400; ++k) EXPECT_NEAR(moved(static_cast<Eigen::Index>(30 * k), 0), command.channels[0][k], 1e-12) << k;
  EXPECT_EQ(std::lround(delay / kNcPeriod), 6);
  EXPECT_EQ(std::lround(delay / instrumentPeriod), 180);
  EXPECT_THROW(resampleTrace(command, delay, EvenTimes{0.0179, instrumentPeriod, 1}), InvalidInput);
  EXPECT_THROW(resampleTrace(command, delay, EvenTimes{0.018, instrumentPeriod, 30 * 399 + 2}), InvalidInput);  // one past the end
}

TEST(Seed004Alignment, RejectsMismatchedChannelsStillAxesAnEmptyWindowAndNoOverlap) {
  const ServoGains exact[5] = {{40, 1}, {45, 1}, {50, 1}, {35, 1}, {30, 1}};
  auto r = record(kOffset, exact);
  auto fewer = r.command;
  fewer.channels.pop_back();
  EXPECT_THROW(estimateClockOffset(fewer, r.encoder), InvalidInput);
  EXPECT_THROW(estimateClockOffset(r.command, r.encoder, {.lowest = 0.1, .highest = 0.1}), InvalidInput);
  EXPECT_THROW(estimateClockOffset(r.command, r.encoder, {.lowest = 20.0, .highest = 30.0}), InvalidInput);
  auto still = r;
  for (auto& channel : still.encoder.channels) std::fill(channel.begin(), channel.end(), 1.0);
  EXPECT_THROW(estimateClockOffset(still.command, still.encoder), InvalidInput);
}

}  // namespace
}  // namespace mtacc
