#include "mtacc/procedures/iso230_2.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

double sampleDeviation(const Eigen::VectorXd& x) {
  const double mean = x.mean();
  return std::sqrt((x.array() - mean).square().sum() / static_cast<double>(x.size() - 1));
}

}  // namespace

PositioningResult evaluatePositioning(const PositioningTest& test) {
  const auto m = static_cast<Eigen::Index>(test.targets.size());
  const Eigen::Index n = test.forward.cols();
  if (m < 2 || n < 2 || test.forward.rows() != m || test.backward.rows() != m || test.backward.cols() != n)
    throw InvalidInput("ISO 230-2: needs at least 2 targets and 2 cycles in both directions, one row per target");
  PositioningResult r;
  r.cycles = static_cast<int>(n);
  double upHigh = -INFINITY, upLow = INFINITY, downHigh = -INFINITY, downLow = INFINITY;
  double meanUpHigh = -INFINITY, meanUpLow = INFINITY, meanDownHigh = -INFINITY, meanDownLow = INFINITY;
  double meanHigh = -INFINITY, meanLow = INFINITY, reversalSum = 0;
  for (Eigen::Index i = 0; i < m; ++i) {
    PositionStatistics p;
    p.target = test.targets[static_cast<size_t>(i)];
    const Eigen::VectorXd up = test.forward.row(i).transpose(), down = test.backward.row(i).transpose();
    p.meanForward = up.mean();
    p.meanBackward = down.mean();
    p.mean = 0.5 * (p.meanForward + p.meanBackward);
    p.reversal = p.meanForward - p.meanBackward;
    p.sForward = sampleDeviation(up);
    p.sBackward = sampleDeviation(down);
    p.repeatabilityForward = 4 * p.sForward;
    p.repeatabilityBackward = 4 * p.sBackward;
    p.repeatability = std::max({2 * p.sForward + 2 * p.sBackward + std::abs(p.reversal), p.repeatabilityForward,
                                p.repeatabilityBackward});
    upHigh = std::max(upHigh, p.meanForward + 2 * p.sForward);
    upLow = std::min(upLow, p.meanForward - 2 * p.sForward);
    downHigh = std::max(downHigh, p.meanBackward + 2 * p.sBackward);
    downLow = std::min(downLow, p.meanBackward - 2 * p.sBackward);
    meanUpHigh = std::max(meanUpHigh, p.meanForward);
    meanUpLow = std::min(meanUpLow, p.meanForward);
    meanDownHigh = std::max(meanDownHigh, p.meanBackward);
    meanDownLow = std::min(meanDownLow, p.meanBackward);
    meanHigh = std::max(meanHigh, p.mean);
    meanLow = std::min(meanLow, p.mean);
    r.reversal = std::max(r.reversal, std::abs(p.reversal));
    reversalSum += p.reversal;
    r.repeatabilityForward = std::max(r.repeatabilityForward, p.repeatabilityForward);
    r.repeatabilityBackward = std::max(r.repeatabilityBackward, p.repeatabilityBackward);
    r.repeatability = std::max(r.repeatability, p.repeatability);
    r.positions.push_back(p);
  }
  r.meanReversal = reversalSum / static_cast<double>(m);
  r.accuracyForward = upHigh - upLow;
  r.accuracyBackward = downHigh - downLow;
  r.accuracy = std::max(upHigh, downHigh) - std::min(upLow, downLow);
  r.systematicForward = meanUpHigh - meanUpLow;
  r.systematicBackward = meanDownHigh - meanDownLow;
  r.systematic = std::max(meanUpHigh, meanDownHigh) - std::min(meanUpLow, meanDownLow);
  r.meanDeviationRange = meanHigh - meanLow;
  if (n < 5) r.notes.push_back(fmt::format("{} cycles: ISO 230-2 asks for 5 in each direction", n));
  if (m < 5) r.notes.push_back(fmt::format("{} target positions: ISO 230-2 asks for at least 5", m));
  if (test.axis == PositioningAxis::Linear) {
    const double length = test.targets.back() - test.targets.front();
    if (length <= 2000.0 && static_cast<double>(m) < 5.0 * length / 1000.0)
      r.notes.push_back(fmt::format("{} target positions over {:g} mm: ISO 230-2 asks for at least 5 per metre", m, length));
  }
  return r;
}

}  // namespace mtacc
