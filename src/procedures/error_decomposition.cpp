#include "mtacc/procedures/error_decomposition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

void check(const DecompositionTest& t, size_t index, MotionParameter parameter) {
  const size_t n = t.time.size();
  if (n < 2) throw InvalidInput(fmt::format("decomposition test {} (F {:g}): {} samples, at least 2 needed", index, t.feed, n));
  if (t.measured.size() != n || t.encoder.size() != n || t.nominal.size() != n || t.link.size() != n ||
      (!t.acceleration.empty() && t.acceleration.size() != n))
    throw InvalidInput(fmt::format("decomposition test {} (F {:g}): its series have different lengths", index, t.feed));
  for (size_t i = 1; i < n; ++i)
    if (!(t.time[i] > t.time[i - 1]))
      throw InvalidInput(fmt::format("decomposition test {} (F {:g}): time does not increase at sample {}", index, t.feed, i));
  if (parameter != MotionParameter::Path) return;
  if (!t.workpieceRotation.empty() && t.workpieceRotation.size() != n)
    throw InvalidInput(fmt::format("decomposition test {} (F {:g}): its workpiece rotations have another length", index, t.feed));
  if (t.path.size() != n) throw InvalidInput(fmt::format("decomposition test {} (F {:g}): its path has another length", index, t.feed));
  for (size_t i = 1; i < n; ++i)
    if (!(t.path[i] >= t.path[i - 1]))
      throw InvalidInput(fmt::format("decomposition test {} (F {:g}): the path decreases at sample {}", index, t.feed, i));
  if (!(t.path.back() > t.path.front()))
    throw InvalidInput(fmt::format("decomposition test {} (F {:g}): the path does not advance", index, t.feed));
}

// The parameter (time or path) from the test's first sample to its last scaled to [-1, 1]:
// x = 2 t_n - 1 with t_n in [0, 1] (O5).
struct Normalised {
  const LargeVector<double>& along;
  double start, span;
  Normalised(const DecompositionTest& t, MotionParameter parameter)
      : along(parameter == MotionParameter::Path ? t.path : t.time), start(along.front()), span(along.back() - along.front()) {}
  double operator()(size_t i) const { return 2.0 * (along[i] - start) / span - 1.0; }
};

// The three-term recurrence of the Legendre polynomials, P_0 = 1, P_1 = x,
// P_k+1 = a_k x P_k - b_k P_k-1 with a_k = (2k + 1) / (k + 1), b_k = k / (k + 1).
struct Legendre {
  int degree;
  std::vector<double> a, b;
  explicit Legendre(int d) : degree(d) {
    for (int k = 0; k < d; ++k) a.push_back((2.0 * k + 1) / (k + 1)), b.push_back(static_cast<double>(k) / (k + 1));
  }
  // P_k+1 from P_k and P_k-1 at x.
  double next(int k, double x, double pk, double previous) const {
    return a[static_cast<size_t>(k)] * x * pk - b[static_cast<size_t>(k)] * previous;
  }
  // P_0 .. P_degree at x into p.
  void row(double x, double* p) const {
    p[0] = 1.0;
    if (degree >= 1) p[1] = x;
    for (int k = 1; k < degree; ++k) p[k + 1] = next(k, x, p[k], p[k - 1]);
  }
  // sum_k c_k P_k(x_i) for each sample i (c: degree + 1 rows, three columns), eight samples at a
  // time so that the recurrence runs in the vector lanes rather than along its latency.
  void series(const Normalised& x, size_t n, const Eigen::MatrixXd& c, LargeVector<Vec3>& out) const {
    constexpr size_t kLanes = 8;
    for (size_t i0 = 0; i0 < n; i0 += kLanes) {
      double xs[kLanes], previous[kLanes], current[kLanes], sum[3][kLanes];
      for (size_t l = 0; l < kLanes; ++l) {
        xs[l] = x(std::min(i0 + l, n - 1));
        previous[l] = 1.0;
        current[l] = xs[l];
        for (int d = 0; d < 3; ++d) sum[d][l] = c(0, d) + (degree >= 1 ? c(1, d) * xs[l] : 0.0);
      }
      for (int k = 1; k < degree; ++k)
        for (size_t l = 0; l < kLanes; ++l) {
          const double pk1 = next(k, xs[l], current[l], previous[l]);
          previous[l] = current[l];
          current[l] = pk1;
          for (int d = 0; d < 3; ++d) sum[d][l] += c(k + 1, d) * pk1;
        }
      for (size_t l = 0; l < kLanes && i0 + l < n; ++l) out[i0 + l] = Vec3(sum[0][l], sum[1][l], sum[2][l]);
    }
  }
};

// The least-squares Legendre coefficients (degree + 1 rows, one column per direction) of
// chi - chi_enc - delta_l (the left side of eq. 16) over the samples `fitted`. Householder QR a
// block of rows at a time, each block stacked under the triangle of the rows before it: the
// accuracy of QR on the whole matrix without holding the matrix (samples x degree + 1).
Eigen::MatrixXd fitMotion(const DecompositionTest& t, MotionParameter parameter, int degree, const std::vector<Eigen::Index>& fitted) {
  constexpr Eigen::Index kBlock = 512;
  const Eigen::Index terms = degree + 1, width = terms + 3;
  const Normalised x(t, parameter);
  const Legendre legendre(degree);
  Eigen::MatrixXd stack(width + kBlock, width);  // [R of the rows so far; the next block], basis | right side
  Eigen::Index kept = 0;  // rows of R held (fewer than width until enough rows were seen)
  for (size_t b = 0; b < fitted.size(); b += kBlock) {
    const size_t e = std::min(fitted.size(), b + static_cast<size_t>(kBlock));
    for (size_t k = b; k < e; ++k) {
      const auto i = static_cast<size_t>(fitted[k]);
      const Eigen::Index row = kept + static_cast<Eigen::Index>(k - b);
      double p[61];
      legendre.row(x(i), p);
      for (Eigen::Index c = 0; c < terms; ++c) stack(row, c) = p[c];
      stack.block<1, 3>(row, terms) = (t.measured[i] - t.encoder[i] - t.link[i]).transpose();
    }
    const Eigen::Index rows = kept + static_cast<Eigen::Index>(e - b);
    Eigen::Ref<Eigen::MatrixXd> held = stack.topRows(rows);
    const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> inPlace(held);
    kept = std::min(rows, width);
    stack.topRows(kept) = stack.topRows(kept).triangularView<Eigen::Upper>().toDenseMatrix();
  }
  // [R11 R12; 0 R22]: R11 c = R12 solves the least squares of the basis against the right side.
  return stack.topLeftCorner(terms, terms).triangularView<Eigen::Upper>().solve(stack.block(0, terms, terms, 3));
}

// The reference samples the motion errors are fitted to.
std::vector<Eigen::Index> fittedSamples(const DecompositionTest& t, const DecompositionOptions& o) {
  const auto& a = t.acceleration;
  const bool steady = o.referenceFit == ReferenceFit::Steady && !a.empty();
  const double limit = steady ? o.steadyShare * *std::max_element(a.begin(), a.end()) : 0.0;
  std::vector<Eigen::Index> kept, all;
  for (size_t i = 0; i < t.time.size(); ++i) {
    all.push_back(static_cast<Eigen::Index>(i));
    if (!steady || a[i] <= limit) kept.push_back(static_cast<Eigen::Index>(i));
  }
  // A reference that accelerates throughout has no steady part to leave the rest out for.
  return 2 * kept.size() >= all.size() && kept.size() >= static_cast<size_t>(o.degree) + 2 ? kept : all;
}

}  // namespace

std::vector<DecomposedTest> decomposeErrors(std::vector<DecompositionTest> tests, const DecompositionOptions& o) {
  if (o.referenceTest < 0 || o.referenceTest >= static_cast<int>(tests.size()))
    throw InvalidInput(fmt::format("reference test {} of {} tests", o.referenceTest, tests.size()));
  if (o.degree < 0 || o.degree > 60) throw InvalidInput(fmt::format("motion-error degree {}: give 0 to 60", o.degree));
  if (!(o.steadyShare > 0.0 && o.steadyShare <= 1.0))
    throw InvalidInput(fmt::format("steady share {:g}: give a share of the largest acceleration above 0 and at most 1", o.steadyShare));
  for (size_t k = 0; k < tests.size(); ++k) check(tests[k], k, o.parameter);
  const DecompositionTest& reference = tests[static_cast<size_t>(o.referenceTest)];
  if (reference.time.size() < static_cast<size_t>(o.degree) + 2)
    throw InvalidInput(fmt::format("the reference test has {} samples: a degree-{} fit of the motion errors needs more than {}",
                                            reference.time.size(), o.degree, o.degree + 1));
  // Eqs. 16-17: in the reference test everything beyond the link errors is motion error, up to
  // the dynamic residue the fit leaves; the fit's coefficients carry delta_m to the other tests.
  const auto fitted = fittedSamples(reference, o);
  const Eigen::MatrixXd coefficients = fitMotion(reference, o.parameter, o.degree, fitted);
  const Legendre legendre(o.degree);
  std::vector<DecomposedTest> out;
  out.reserve(tests.size());
  for (size_t k = 0; k < tests.size(); ++k) {
    DecomposedTest d;
    d.recorded = std::move(tests[k]);
    const DecompositionTest& t = d.recorded;
    const size_t n = t.time.size();
    d.contouring.resize(n);
    d.motion.resize(n);
    d.dynamic.resize(n);
    legendre.series(Normalised(t, o.parameter), n, coefficients, d.motion);
    // Eq. 18: the drift is the mean of what neither link nor motion errors explain, taken in the
    // drift frame; the reference test's is zero because its fit has the constant term.
    d.driftInMachineFrame = o.driftFrame == DriftFrame::Machine && !t.workpieceRotation.empty();
    Vec3 sum = Vec3::Zero();
    for (size_t i = 0; i < n; ++i) {
      d.dynamic[i] = t.measured[i] - t.encoder[i] - t.link[i] - d.motion[i];  // the rest, before the drift
      sum += d.driftInMachineFrame ? Vec3(t.workpieceRotation[i] * d.dynamic[i]) : d.dynamic[i];
    }
    d.drift = static_cast<int>(k) == o.referenceTest ? Vec3::Zero() : Vec3(sum / static_cast<double>(n));
    if (static_cast<int>(k) == o.referenceTest) d.leftOutOfFit = n - fitted.size();
    for (size_t i = 0; i < n; ++i) {
      d.contouring[i] = t.encoder[i] - t.nominal[i];
      d.dynamic[i] -= d.driftAt(i);
    }
    d.contouringOrthogonal = orthogonalToPath(d.contouring, t.nominal, d.orthogonalUndefined);
    out.push_back(std::move(d));
  }
  return out;
}

LargeVector<Vec3> orthogonalToPath(std::span<const Vec3> deviation, std::span<const Vec3> nominal, size_t& undefined, double still) {
  const size_t n = nominal.size();
  if (deviation.size() != n)
    throw InvalidInput(fmt::format("{} deviations for {} samples of the path", deviation.size(), n));
  LargeVector<Vec3> out(n, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  undefined = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 step = nominal[std::min(i + 1, n - 1)] - nominal[i == 0 ? 0 : i - 1];
    if (step.norm() < still) {
      ++undefined;
      continue;
    }
    const Vec3 tangent = step.normalized();
    out[i] = deviation[i] - tangent * tangent.dot(deviation[i]);
  }
  return out;
}

DecompositionShares decompositionShares(const DecomposedTest& test) {
  DecompositionShares s;
  int counted3 = 0, counted5 = 0;
  for (size_t i = 0; i < test.contouring.size(); ++i) {
    const double c = test.contouring[i].norm(), qs = test.quasiStatic(i).norm(), d = test.dynamic[i].norm();
    const double l = test.recorded.link[i].norm(), m = test.motion[i].norm(), td = test.drift.norm();
    const double printed = c + qs + d, split = c + l + m + td + d;
    if (printed > 0) {
      const double over = 1.0 / printed;
      s.contouring += c * over;
      s.quasiStatic += qs * over;
      s.dynamic += d * over;
      s.splitOverPrinted += split * over;
      ++counted3;
    }
    if (split > 0) {
      const double over = 1.0 / split;
      s.splitContouring += c * over;
      s.link += l * over;
      s.motion += m * over;
      s.drift += td * over;
      s.splitDynamic += d * over;
      ++counted5;
    }
  }
  const double to3 = counted3 > 0 ? 100.0 / counted3 : 0.0, to5 = counted5 > 0 ? 100.0 / counted5 : 0.0;
  for (double* v : {&s.contouring, &s.quasiStatic, &s.dynamic, &s.splitOverPrinted}) *v *= to3;
  for (double* v : {&s.splitContouring, &s.link, &s.motion, &s.drift, &s.splitDynamic}) *v *= to5;
  return s;
}

DirectionStatistics directionStatistics(std::span<const Vec3> series) {
  DirectionStatistics s;
  size_t counted = 0;
  for (const Vec3& v : series) {
    if (!v.allFinite()) continue;
    s.maximum = s.maximum.cwiseMax(v.cwiseAbs());
    s.rms += v.cwiseProduct(v);
    ++counted;
  }
  if (counted > 0) s.rms = (s.rms / static_cast<double>(counted)).cwiseSqrt();
  return s;
}

PowerLaw fitPowerLaw(const std::vector<double>& feeds, const std::vector<double>& values) {
  if (feeds.size() != values.size() || feeds.size() < 2)
    throw InvalidInput(fmt::format("a power law needs two or more feeds, each with a value ({} feeds, {} values)", feeds.size(), values.size()));
  const auto n = static_cast<Eigen::Index>(feeds.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double f = feeds[static_cast<size_t>(i)], v = values[static_cast<size_t>(i)];
    if (!(f > 0) || !(v > 0) || !std::isfinite(f) || !std::isfinite(v))
      throw InvalidInput(fmt::format("a power law needs positive feeds and values (feed {:g}, value {:g})", f, v));
    a(i, 0) = 1.0;
    a(i, 1) = std::log(f);
    b[i] = std::log(v);
  }
  if (a.col(1).maxCoeff() == a.col(1).minCoeff()) throw InvalidInput("a power law needs at least two different feeds");
  const Eigen::Vector2d x = a.colPivHouseholderQr().solve(b);
  PowerLaw p{std::exp(x[0]), x[1], 0.0};
  for (size_t i = 0; i < feeds.size(); ++i)
    p.largestRelativeMisfit = std::max(p.largestRelativeMisfit, std::abs(p.kappa * std::pow(feeds[i], p.exponent) / values[i] - 1.0));
  return p;
}

std::vector<double> geometricFeeds(double first, double ratio, int count) {
  std::vector<double> feeds;
  for (int k = 0; k < count; ++k) feeds.push_back(first * std::pow(ratio, k));
  return feeds;
}

}  // namespace mtacc
