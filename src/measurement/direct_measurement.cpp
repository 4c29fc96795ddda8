#include "mtacc/measurement/direct_measurement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Eigen::VectorXd rowScatter(const Eigen::MatrixXd& m) {
  const Eigen::VectorXd mean = m.rowwise().mean();
  return ((m.colwise() - mean).array().square().rowwise().sum() / static_cast<double>(std::max<Eigen::Index>(m.cols() - 1, 1))).sqrt();
}

}  // namespace

ComponentRuns simulateComponentRuns(const AxisErrors& axis, int component, const ComponentRunsSpec& spec) {
  ComponentRuns r;
  r.positions = spec.positions;
  const auto m = static_cast<Eigen::Index>(spec.positions.size());
  for (auto* matrix : {&r.forward, &r.backward, &r.forwardTime, &r.backwardTime}) matrix->resize(m, spec.runs);
  std::mt19937_64 rng(spec.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  double time = 0.0, nextDisturbance = spec.disturbanceAmplitude != 0.0 ? 0.5 * spec.disturbanceInterval : INFINITY;
  auto read = [&](Eigen::Index i, int direction) {
    const double x = spec.positions[static_cast<size_t>(i)];
    double v = axis.motion[static_cast<size_t>(component)].value(x, direction);
    if (component < 3) {
      const Vec3 rotation(axis.motion[3].value(x, direction), axis.motion[4].value(x, direction), axis.motion[5].value(x, direction));
      v += rotation.cross(spec.abbeOffset)[component];
    }
    v += spec.noise * noise(rng);
    if (spec.settlingOffset != 0.0) v += spec.settlingOffset * std::exp(-time / spec.settlingTime);
    if (time >= nextDisturbance) {
      v += spec.disturbanceAmplitude;
      nextDisturbance += spec.disturbanceInterval;
    }
    return v;
  };
  for (int j = 0; j < spec.runs; ++j) {
    for (Eigen::Index i = 0; i < m; ++i, time += spec.readingTime) {
      r.forwardTime(i, j) = time;
      r.forward(i, j) = read(i, 1);
    }
    for (Eigen::Index i = m - 1; i >= 0; --i, time += spec.readingTime) {
      r.backwardTime(i, j) = time;
      r.backward(i, j) = read(i, -1);
    }
  }
  return r;
}

ComponentRuns withoutRuns(const ComponentRuns& r, const std::vector<int>& left) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index j = 0; j < r.forward.cols(); ++j)
    if (std::find(left.begin(), left.end(), static_cast<int>(j)) == left.end()) kept.push_back(j);
  const bool timed = r.forwardTime.size() > 0;
  return {r.positions, r.forward(Eigen::all, kept), r.backward(Eigen::all, kept),
          timed ? Eigen::MatrixXd(r.forwardTime(Eigen::all, kept)) : Eigen::MatrixXd(),
          timed ? Eigen::MatrixXd(r.backwardTime(Eigen::all, kept)) : Eigen::MatrixXd()};
}

ComponentCurve averageRuns(const ComponentRuns& r) {
  ComponentCurve c;
  c.positions = r.positions;
  c.meanForward = r.forward.rowwise().mean();
  c.meanBackward = r.backward.rowwise().mean();
  c.mean = 0.5 * (c.meanForward + c.meanBackward);
  c.reversal = c.meanForward - c.meanBackward;
  // The pooled scatter of one reading about its direction's mean.
  c.scatter = (0.5 * (rowScatter(r.forward).array().square() + rowScatter(r.backward).array().square())).sqrt();
  return c;
}

namespace {

// Each reading's departure from the mean of the runs `kept` at its position and direction.
std::vector<DisturbedReading> departures(const ComponentRuns& r, const std::vector<Eigen::Index>& kept) {
  std::vector<DisturbedReading> all;
  const bool timed = r.forwardTime.size() > 0;
  for (const bool forward : {true, false}) {
    const Eigen::MatrixXd& m = forward ? r.forward : r.backward;
    const Eigen::VectorXd mean = m(Eigen::all, kept).rowwise().mean();
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (const Eigen::Index j : kept)
        all.push_back({static_cast<int>(j), forward, r.positions[static_cast<size_t>(i)], m(i, j) - mean[i],
                       timed ? (forward ? r.forwardTime : r.backwardTime)(i, j) : std::numeric_limits<double>::quiet_NaN()});
  }
  return all;
}

double robustSigmaOf(const std::vector<DisturbedReading>& all) {
  std::vector<double> sizes;
  for (const auto& d : all) sizes.push_back(std::abs(d.departure));
  return 1.4826 * median(sizes);
}

}  // namespace

Disturbances findDisturbances(const ComponentRuns& r, double threshold) {
  Disturbances out;
  std::vector<Eigen::Index> kept(static_cast<size_t>(r.forward.cols()));
  std::iota(kept.begin(), kept.end(), Eigen::Index{0});
  const auto everyRun = departures(r, kept);
  const double readingSigma = robustSigmaOf(everyRun);
  if (!(readingSigma > 0.0)) return out;
  std::vector<double> runMeans(kept.size(), 0.0);
  for (const auto& d : everyRun) runMeans[static_cast<size_t>(d.run)] += d.departure / static_cast<double>(2 * r.forward.rows());
  const double settled = median(runMeans);
  std::vector<double> spread;
  for (double m : runMeans) spread.push_back(std::abs(m - settled));
  const double runSigma = std::max(1.4826 * median(spread), readingSigma / std::sqrt(static_cast<double>(2 * r.forward.rows())));
  for (size_t j = 0; j < runMeans.size() && std::abs(runMeans[j] - settled) > threshold * runSigma; ++j)
    out.unsettledRuns.push_back(static_cast<int>(j));
  // Single readings are judged among the settled runs only, so that a drift is not read as peaks.
  kept.erase(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(std::min(out.unsettledRuns.size(), kept.size() - 2)));
  const auto all = departures(r, kept);
  const double robustSigma = robustSigmaOf(all);
  if (!(robustSigma > 0.0)) return out;
  const bool timed = r.forwardTime.size() > 0;
  for (const auto& d : all)
    if (std::abs(d.departure) > threshold * robustSigma) out.readings.push_back(d);
  if (timed && out.readings.size() >= 3) {
    std::vector<double> times;
    for (const auto& d : out.readings) times.push_back(d.time);
    std::sort(times.begin(), times.end());
    std::vector<double> gaps;
    for (size_t k = 1; k < times.size(); ++k) gaps.push_back(times[k] - times[k - 1]);
    const double typical = median(gaps);
    const bool steady = typical > 0.0 && std::all_of(gaps.begin(), gaps.end(), [&](double g) {
      const double cycles = std::round(g / typical);  // a missed peak leaves a double gap
      return cycles >= 1.0 && std::abs(g - cycles * typical) <= 0.1 * typical;
    });
    if (steady) out.interval = typical;
  }
  return out;
}

double abbeCorrected(double reading, const Vec3& rotation, const Vec3& offset, int component) {
  return reading - rotation.cross(offset)[component];
}

double scaleTemperatureCorrected(double reading, double position, double x0, double temperature, double reference, double alpha) {
  return reading - alpha * (temperature - reference) * (position - x0);
}

double yryFromStraightness(double ytz1, double ytz2, double y, double xrx, double x1, double x2) {
  if (x1 == x2) throw InvalidInput("yry from straightness: the two X positions must differ");
  return (ytz2 - ytz1 - y * xrx) / (x1 - x2);
}

double squarenessFromBlock(double alpha, double beta, double blockSquareness, const SquarenessSetup& s) {
  return s.reference * alpha + s.other * beta + s.block * blockSquareness;
}

std::vector<double> straightness(const std::vector<double>& x, const std::vector<double>& readings, const std::vector<double>& artefact) {
  if (artefact.size() != readings.size()) throw InvalidInput("straightness: one artefact deviation per reading");
  std::vector<double> y(readings.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = readings[i] - artefact[i];
  const double slope = leastSquaresSlope(x, y);
  double meanX = 0, meanY = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    meanX += x[i] / static_cast<double>(y.size());
    meanY += y[i] / static_cast<double>(y.size());
  }
  for (size_t i = 0; i < y.size(); ++i) y[i] -= meanY + slope * (x[i] - meanX);
  return y;
}

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) throw InvalidInput("least-squares slope: needs two or more points");
  const Eigen::Map<const Eigen::VectorXd> xs(x.data(), static_cast<Eigen::Index>(x.size())), ys(y.data(), static_cast<Eigen::Index>(y.size()));
  const Eigen::VectorXd dx = xs.array() - xs.mean();
  const double sxx = dx.squaredNorm();
  if (!(sxx > 0.0)) throw InvalidInput("least-squares slope: the positions must differ");
  return dx.dot(ys.array().matrix() - Eigen::VectorXd::Constant(ys.size(), ys.mean())) / sxx;
}

}  // namespace mtacc
