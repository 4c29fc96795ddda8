#include "mtacc/core/symmetric_eigen.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Householder>

namespace mtacc {

namespace {

constexpr int kLanes = Eigen::internal::packet_traits<double>::size;
using Packet = Eigen::Array<double, kLanes, 1>;

// One matrix's QR iteration: its tridiagonal (d, e: e[i] joins rows i and i + 1), the
// rotations so far applied to the eigenvector matrix q (column-major, its rows padded with
// zeros to whole vector registers, ld of them), and the sweep in progress over rows start..end.
class QrSweeps {
 public:
  QrSweeps(double* d, double* e, double* q, int n, int ld) : d_(d), e_(e), q_(q), n_(n), ld_(ld), end_(n - 1) {
    beginSweep();
  }
  bool done() const { return done_; }
  bool converged() const { return end_ <= 0; }

  // The next rotation of the sweep, G = [c s; -s c] in rows and columns k, k + 1: T <- G^T T G
  // (it zeroes the bulge z below x), Q <- Q G.
  void rotate() {
    const int k = k_;
    const double r = std::sqrt(x_ * x_ + z_ * z_);
    double c = 1, s = 0;
    if (r > 0) {
      const double inverse = 1 / r;
      c = x_ * inverse, s = -z_ * inverse;
    }
    if (k > start_) e_[k - 1] = r;
    const double dk = d_[k], dk1 = d_[k + 1], ek = e_[k], cs = c * s;
    d_[k] = c * c * dk - 2 * cs * ek + s * s * dk1;
    d_[k + 1] = s * s * dk + 2 * cs * ek + c * c * dk1;
    e_[k] = cs * (dk - dk1) + (c * c - s * s) * ek;
    if (k + 1 < end_) x_ = e_[k], z_ = -s * e_[k + 1], e_[k + 1] *= c;
    double* qk = q_ + static_cast<ptrdiff_t>(k) * ld_;
    double* qk1 = qk + ld_;
    for (int i = 0; i < ld_; i += kLanes) {
      const Packet u = Eigen::Map<const Packet>(qk + i), v = Eigen::Map<const Packet>(qk1 + i);
      Eigen::Map<Packet>(qk + i) = c * u - s * v;
      Eigen::Map<Packet>(qk1 + i) = s * u + c * v;
    }
    if (++k_ == end_) beginSweep();
  }

 private:
  // Sets negligible couplings to zero (|e_i| <= eps (|d_i| + |d_i+1|)), takes the last block
  // that is not yet diagonal and Wilkinson's shift from its trailing 2 x 2.
  void beginSweep() {
    constexpr double eps = std::numeric_limits<double>::epsilon(), tiny = std::numeric_limits<double>::min();
    for (int i = 0; i < end_; ++i)
      if (std::abs(e_[i]) <= eps * (std::abs(d_[i]) + std::abs(d_[i + 1])) || std::abs(e_[i]) < tiny) e_[i] = 0;
    while (end_ > 0 && e_[end_ - 1] == 0) --end_;
    if (end_ <= 0 || ++sweeps_ > 30 * n_) {
      done_ = true;
      return;
    }
    start_ = end_ - 1;
    while (start_ > 0 && e_[start_ - 1] != 0) --start_;
    const double half = 0.5 * (d_[end_ - 1] - d_[end_]), e = e_[end_ - 1];
    const double h = std::hypot(half, e);
    const double shift = d_[end_] - e * (e / (half + (half >= 0 ? h : -h)));
    k_ = start_, x_ = d_[start_] - shift, z_ = e_[start_];
  }

  double *d_, *e_, *q_;
  int n_, ld_, start_ = 0, end_, k_ = 0, sweeps_ = 0;
  double x_ = 0, z_ = 0;
  bool done_ = false;
};

bool lowerTriangleFinite(const Eigen::MatrixXd& a, double& largest) {
  largest = 0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    const auto column = a.col(j).tail(a.rows() - j);
    if (!column.allFinite()) return false;
    largest = std::max(largest, column.cwiseAbs().maxCoeff());
  }
  return true;
}

// The state of one matrix between its tridiagonalisation and its sorted output.
struct Problem {
  Eigen::VectorXd d, e;
  Eigen::MatrixXd q;
  double scale = 0;
};

// A / scale to tridiagonal form T = Q^T A Q / scale; Q accumulated reflector by reflector from
// the last (Eigen's blocked accumulation takes half as long again at these sizes).
void tridiagonalise(const Eigen::MatrixXd& a, Problem& p) {
  const Eigen::Index n = a.rows(), ld = (n + kLanes - 1) / kLanes * kLanes;
  thread_local Eigen::Tridiagonalization<Eigen::MatrixXd> tri;
  thread_local Eigen::VectorXd work;
  tri.compute((a / p.scale).triangularView<Eigen::Lower>());
  p.d = tri.diagonal();
  p.e.setZero(n);
  p.e.head(n - 1) = tri.subDiagonal();
  p.q.setIdentity(ld, n);
  work.resize(n);
  const Eigen::MatrixXd& reflectors = tri.packedMatrix();
  for (Eigen::Index k = n - 2; k >= 0; --k) {
    const Eigen::Index m = n - k - 1;
    p.q.block(k + 1, k + 1, m, m).applyHouseholderOnTheLeft(reflectors.col(k).tail(m - 1), tri.householderCoefficients()[k],
                                                           work.data());
  }
}

void sortedOutput(const Problem& p, SymmetricEigen& out) {
  const Eigen::Index n = p.d.size();
  std::vector<Eigen::Index> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index i, Eigen::Index j) { return p.d[i] < p.d[j]; });
  out.values.resize(n);
  out.vectors.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.values[i] = p.scale * p.d[order[static_cast<size_t>(i)]];
    out.vectors.col(i) = p.q.col(order[static_cast<size_t>(i)]).head(n);
  }
}

}  // namespace

void symmetricEigen(std::span<const Eigen::MatrixXd> matrices, std::span<SymmetricEigen> out) {
  thread_local std::array<Problem, kInterleavedEigenproblems> problems;
  for (size_t first = 0; first < matrices.size(); first += kInterleavedEigenproblems) {
    const size_t count = std::min(kInterleavedEigenproblems, matrices.size() - first);
    std::vector<QrSweeps> sweeps;
    std::array<size_t, kInterleavedEigenproblems> index{};
    for (size_t i = 0; i < count; ++i) {
      const Eigen::MatrixXd& a = matrices[first + i];
      SymmetricEigen& result = out[first + i];
      Problem& p = problems[i];
      const Eigen::Index n = a.rows();
      result.converged = lowerTriangleFinite(a, p.scale);
      if (!result.converged) continue;
      if (p.scale == 0 || n == 1) {  // already diagonal
        result.values = a.diagonal();
        result.vectors.setIdentity(n, n);
        continue;
      }
      tridiagonalise(a, p);
      index[sweeps.size()] = i;
      sweeps.emplace_back(p.d.data(), p.e.data(), p.q.data(), static_cast<int>(n), static_cast<int>(p.q.rows()));
    }
    for (bool running = true; running;) {
      running = false;
      for (QrSweeps& s : sweeps)
        if (!s.done()) s.rotate(), running = true;
    }
    for (size_t j = 0; j < sweeps.size(); ++j) {
      SymmetricEigen& result = out[first + index[j]];
      result.converged = sweeps[j].converged();
      if (result.converged) sortedOutput(problems[index[j]], result);
    }
  }
}

}  // namespace mtacc
