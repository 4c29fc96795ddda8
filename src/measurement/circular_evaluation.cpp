#include "mtacc/measurement/circular_evaluation.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

void requireCircular(const MeasurementRun& run) {
  if (run.instrument != Instrument::Ballbar) throw InvalidInput(run.name + ": not a ballbar run");
  if (run.angle.size() != static_cast<size_t>(run.poses()) || run.readings.rows() != run.poses())
    throw InvalidInput(run.name + ": a circular evaluation needs an angle and a reading per pose");
  if (run.poses() < 8) throw InvalidInput(run.name + ": too few points for a circle (at least 8)");
  std::vector<double> around;
  for (double a : run.angle) around.push_back(std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi));
  std::sort(around.begin(), around.end());
  double gap = around.front() + 2 * kPi - around.back();
  for (size_t i = 1; i < around.size(); ++i) gap = std::max(gap, around[i] - around[i - 1]);
  constexpr double kSmallestArc = kPi / 2;  // a partial arc (ISO 230-4) of at least 90 deg
  if (2 * kPi - gap < kSmallestArc)
    throw InvalidInput(fmt::format("{}: the points cover only {:.4g} deg of the circle; a circular evaluation "
                                            "needs an arc of at least 90 deg", run.name, (2 * kPi - gap) / kDeg));
}

int senseOf(const MeasurementRun& run, size_t i) { return run.sense.size() > i ? run.sense[i] : 1; }
double sgn(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

double wrapAngle(double a) {
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}

// Linear interpolation of a periodic sampled function at angle a.
double periodicInterpolate(std::vector<std::pair<double, double>> samples, double a) {
  std::sort(samples.begin(), samples.end());
  a = wrapAngle(a);
  auto hi = std::lower_bound(samples.begin(), samples.end(), std::make_pair(a, -1e300));
  const auto& p1 = hi == samples.end() ? samples.front() : *hi;
  const auto& p0 = hi == samples.begin() ? samples.back() : *(hi - 1);
  double span = p1.first - p0.first;
  double along = a - p0.first;
  if (span <= 0) span += 2 * kPi;
  if (along < 0) along += 2 * kPi;
  return span > 0 ? p0.second + (p1.second - p0.second) * along / span : p0.second;
}

}  // namespace

EccentricityFit fitEccentricity(const MeasurementRun& run, bool secondHarmonics) {
  requireCircular(run);
  const Eigen::Index n = run.poses();
  Eigen::MatrixXd a(n, secondHarmonics ? 5 : 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = run.angle[static_cast<size_t>(i)];
    a(i, 0) = 1, a(i, 1) = std::cos(t), a(i, 2) = std::sin(t);
    if (secondHarmonics) a(i, 3) = std::cos(2 * t), a(i, 4) = std::sin(2 * t);
  }
  const Eigen::VectorXd y = run.readings.col(0);
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  EccentricityFit f;
  f.offset = c[0], f.e1 = c[1], f.e2 = c[2];
  f.eccentricity = f.e1 * run.plotAxes[0] + f.e2 * run.plotAxes[1];
  if (secondHarmonics) f.cos2 = c[3], f.sin2 = c[4];
  f.rms = std::sqrt((y - a * c).squaredNorm() / static_cast<double>(n));
  return f;
}

CircularTestResult evaluateCircularTest(const MeasurementRun& run) {
  requireCircular(run);
  CircularTestResult out;
  out.eccentricity = fitEccentricity(run, false);
  const Eigen::Index n = run.poses();
  const Eigen::VectorXd y = run.readings.col(0);

  // Radial deviation about the least-squares circle (centre and radius removed).
  std::vector<std::pair<double, double>> ccw, cw;
  for (int sense : {1, -1}) {
    CircularDirection d;
    d.sense = sense;
    double lo = 1e300, hi = -1e300, fLo = 1e300, fHi = -1e300;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (senseOf(run, static_cast<size_t>(i)) != sense) continue;
      const double t = run.angle[static_cast<size_t>(i)];
      const double r = y[i] - out.eccentricity.offset - out.eccentricity.e1 * std::cos(t) -
                       out.eccentricity.e2 * std::sin(t);
      lo = std::min(lo, r), hi = std::max(hi, r);
      fLo = std::min(fLo, y[i]), fHi = std::max(fHi, y[i]);
      (sense > 0 ? ccw : cw).emplace_back(wrapAngle(t), r);
    }
    if (hi < lo) continue;
    d.circularDeviation = hi - lo, d.radialMax = fHi, d.radialMin = fLo;
    out.directions.push_back(d);
  }
  out.bothDirections = ccw.size() >= 4 && cw.size() >= 4;
  if (out.bothDirections)
    for (const auto& [t, r] : ccw) out.hysteresis = std::max(out.hysteresis, std::abs(r - periodicInterpolate(cw, t)));

  // Diagnostics.
  const int columns = out.bothDirections ? 8 : 7;
  Eigen::MatrixXd a(n, columns);
  // Directions of motion of a and b towards the next sample (as the path's axis directions).
  double va = 0, vb = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = run.angle[static_cast<size_t>(i)];
    const double s = senseOf(run, static_cast<size_t>(i));
    if (i + 1 < n) {
      const double next = run.angle[static_cast<size_t>(i + 1)];
      const double da = std::cos(next) - std::cos(t), db = std::sin(next) - std::sin(t);
      if (std::abs(da) > 1e-12) va = sgn(da);
      if (std::abs(db) > 1e-12) vb = sgn(db);
    }
    int c = 0;
    a(i, c++) = 1, a(i, c++) = std::cos(t), a(i, c++) = std::sin(t), a(i, c++) = std::cos(2 * t),
        a(i, c++) = std::sin(2 * t);
    a(i, c++) = va * std::cos(t), a(i, c++) = vb * std::sin(t);
    if (out.bothDirections) a(i, c++) = s * std::sin(2 * t);
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd residual = y - a * c;
  auto& g = out.diagnostics;
  const double radius = run.setup.length;
  g.scaleMismatch = 2 * c[3] / radius;
  g.squareness = -2 * c[4] / radius;
  g.backlashA = -2 * c[5];
  g.backlashB = -2 * c[6];
  if (out.bothDirections) g.servoMismatch = 2 * c[7] / (run.feed / 60.0);
  g.residualRms = std::sqrt(residual.squaredNorm() / static_cast<double>(n));
  const double window = 10 * kDeg;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = wrapAngle(run.angle[static_cast<size_t>(i)]);
    const double r = std::abs(residual[i]);
    const double toA = std::min({t, std::abs(t - kPi), 2 * kPi - t});
    const double toB = std::min(std::abs(t - kPi / 2), std::abs(t - 3 * kPi / 2));
    if (toA < window) g.reversalSpikeA = std::max(g.reversalSpikeA, r);
    if (toB < window) g.reversalSpikeB = std::max(g.reversalSpikeB, r);
  }
  return out;
}

}  // namespace mtacc
