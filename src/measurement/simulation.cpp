#include "mtacc/measurement/simulation.hpp"

#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::vector<double> runTimes(const KinematicModel& nominal, const MeasurementRun& run) {
  if (run.feed <= 0) throw InvalidInput("the feed must be positive");
  std::vector<double> t(static_cast<size_t>(run.poses()), 0.0);
  Vec3 previous = Vec3::Zero();
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    const Vec3 p = toolInWorkpiece(nominal, run.q.row(i).data()) * run.setup.toolBall;
    if (i > 0) t[static_cast<size_t>(i)] = t[static_cast<size_t>(i - 1)] + (p - previous).norm() / (run.feed / 60.0);
    previous = p;
  }
  return t;
}

JointMatrix disturbedPoses(const KinematicModel& nominal, const MeasurementRun& run, const Disturbance& d) {
  JointMatrix q = run.q;
  if (d.empty() || run.poses() < 2) return q;
  const auto t = runTimes(nominal, run);
  const Eigen::Index n = run.poses();
  for (Eigen::Index j = 0; j < q.cols(); ++j) {
    const auto J = static_cast<size_t>(j);
    const double lag = J < d.lag.size() ? d.lag[J] : 0.0;
    const double backlash = J < d.backlash.size() ? d.backlash[J] : 0.0;
    const double spike = J < d.spikeHeight.size() ? d.spikeHeight[J] : 0.0;
    double lastReversal = -1e300;
    int lastSign = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index a = std::max<Eigen::Index>(i - 1, 0), b = std::min<Eigen::Index>(i + 1, n - 1);
      const double dt = t[static_cast<size_t>(b)] - t[static_cast<size_t>(a)];
      const double v = dt > 0 ? (run.q(b, j) - run.q(a, j)) / dt : 0.0;
      const int sign = run.direction.size() ? run.direction(i, j) : (std::abs(v) < 1e-9 ? lastSign : (v > 0 ? 1 : -1));
      if (sign != lastSign && lastSign != 0) lastReversal = t[static_cast<size_t>(i)];
      lastSign = sign;
      double error = -lag * v - 0.5 * backlash * sign;
      if (spike != 0.0 && lastReversal > -1e299)
        error -= spike * sign * std::exp(-(t[static_cast<size_t>(i)] - lastReversal) / d.spikeTime);
      q(i, j) += error;
    }
  }
  return q;
}

void simulateRun(const KinematicModel& model, const KinematicModel& nominal, MeasurementRun& run, const Disturbance& disturbance,
                 double noise, std::mt19937_64* rng) {
  MeasurementRun actual = run;
  actual.q = disturbedPoses(nominal, run, disturbance);
  run.readings = predictReadings(model, nominal, actual);
  if (noise > 0) {
    if (!rng) throw InvalidInput("noise needs a random generator");
    std::normal_distribution<double> gauss(0.0, noise);
    for (Eigen::Index i = 0; i < run.readings.size(); ++i) run.readings.data()[i] += gauss(*rng);
  }
}

}  // namespace mtacc
