// spikeSamples against a plain implementation of its definition (the median of each window by
// std::nth_element on a copy, the robust scale from the median absolute departure).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mtacc/procedures/signal_spikes.hpp"

using namespace mtacc;

namespace {

double medianOf(std::vector<double> v) {
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

std::vector<size_t> spikesByDefinition(const SampledTrace& trace, double threshold, double floor) {
  const size_t n = trace.samples(), half = kSpikeWindow / 2;
  std::vector<bool> flagged(n, false);
  for (const auto& channel : trace.channels) {
    std::vector<double> magnitude(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t from = std::min(i > half ? i - half : 0, n - kSpikeWindow);
      const std::vector<double> window(channel.begin() + static_cast<std::ptrdiff_t>(from),
                                       channel.begin() + static_cast<std::ptrdiff_t>(from + kSpikeWindow));
      magnitude[i] = std::abs(channel[i] - medianOf(window));
    }
    const double limit = std::max(threshold * 1.4826 * medianOf(magnitude), floor);
    for (size_t i = 0; i < n; ++i) flagged[i] = flagged[i] || magnitude[i] > limit;
  }
  std::vector<size_t> out;
  for (size_t i = 0; i < n; ++i)
    if (flagged[i]) out.push_back(i);
  return out;
}

// Three channels as an instrument records them (the tool ball's deviation, mm): a few
// micrometres varying smoothly, 0.2 um of noise, spikes of 50 um at the given samples of channel 1.
SampledTrace noisyTrace(size_t n, const std::vector<size_t>& spikes, unsigned seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> noise(0.0, 2e-4);
  SampledTrace t{0.0, 1e-4, std::vector<std::vector<double>>(3, std::vector<double>(n))};
  for (size_t c = 0; c < 3; ++c)
    for (size_t i = 0; i < n; ++i) t.channels[c][i] = 5e-3 * std::sin(1e-3 * static_cast<double>(i) + static_cast<double>(c)) + noise(random);
  for (size_t i : spikes) t.channels[1][i] += 0.05;
  return t;
}

}  // namespace

TEST(SignalSpikes, PlantedSpikesAreFoundAtTheirSamplesAndNothingElse) {
  const std::vector<size_t> planted{0, 1, 500, 2000, 4997, 4999};
  EXPECT_EQ(spikeSamples(noisyTrace(5000, planted, 3)), planted);
}

TEST(SignalSpikes, EverySampleIsJudgedAsTheDefinitionSays) {
  // A low threshold flags a few hundred samples of plain noise: each window's median decides.
  for (unsigned seed : {1u, 2u, 3u}) {
    const SampledTrace t = noisyTrace(3000, {10, 1500}, seed);
    for (double threshold : {2.0, 3.0, 8.0}) {
      const auto expected = spikesByDefinition(t, threshold, 1e-5);
      EXPECT_EQ(spikeSamples(t, threshold), expected) << "seed " << seed << ", threshold " << threshold;
      if (threshold == 2.0) {
        EXPECT_GT(expected.size(), 100u);
      }
    }
  }
}

TEST(SignalSpikes, RepeatedValuesAndShortTraces) {
  // A staircase of repeated values: the medians of windows with ties.
  SampledTrace stairs{0.0, 1.0, {std::vector<double>(200)}};
  for (size_t i = 0; i < 200; ++i) stairs.channels[0][i] = static_cast<double>(i / 3);
  stairs.channels[0][100] += 40.0;
  const auto flagged = spikeSamples(stairs);
  EXPECT_EQ(flagged, spikesByDefinition(stairs, 8.0, 1e-5));
  EXPECT_TRUE(std::find(flagged.begin(), flagged.end(), 100) != flagged.end());
  EXPECT_TRUE(spikeSamples(SampledTrace{0.0, 1.0, {std::vector<double>(kSpikeWindow - 1, 1.0)}}).empty());
  // A noise-free deviation drifting by 1 nm a sample: the median of departures is 0, the floor holds.
  SampledTrace line{0.0, 1.0, {std::vector<double>(100)}};
  for (size_t i = 0; i < 100; ++i) line.channels[0][i] = 1e-6 * static_cast<double>(i);
  EXPECT_TRUE(spikeSamples(line).empty());
}
