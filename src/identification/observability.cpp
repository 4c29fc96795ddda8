#include "mtacc/identification/observability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <thread>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/parallel.hpp"

namespace mtacc {
namespace {

// The triangular factor R of a = QR (a tall), from the factors of two halves (tall-skinny QR):
// R of [R_top; R_bottom], the halves side by side when two threads are allowed; the same
// split on one thread, so that the result does not depend on the thread count. `a` is
// overwritten.
Eigen::MatrixXd triangularFactor(Eigen::Ref<Eigen::MatrixXd> a, int threads) {
  auto factor = [](Eigen::Ref<Eigen::MatrixXd> m) -> Eigen::MatrixXd {
    const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(m);
    return qr.matrixQR().topRows(m.cols()).triangularView<Eigen::Upper>();
  };
  const Eigen::Index n = a.cols(), half = a.rows() / 2;
  if (half < 4 * n) return factor(a);
  Eigen::MatrixXd top;
  std::optional<std::thread> worker;
  if (threadCount(threads) > 1)
    worker.emplace([&] { top = factor(a.topRows(half)); });
  else
    top = factor(a.topRows(half));
  const Eigen::MatrixXd bottom = factor(a.bottomRows(a.rows() - half));
  if (worker) worker->join();
  Eigen::MatrixXd both(2 * n, n);
  both << top, bottom;
  return factor(both);
}

// The singular values and right singular vectors of a small matrix. Eigen 3.4.0's divide and
// conquer SVD (BDCSVD) reads out of bounds in its deflation on some matrices with many singular
// values at rounding level, which an unobservable parameter set gives (the 27 location errors of
// the tilting table on its R-test plan: 48 columns of rank 35 segfaulted). One-sided Jacobi is
// safe, and also gives the null vectors whose supports name the groups of parameters that act
// alike; above 64 columns (a plate campaign's 215) its cost grows past the divide and conquer's
// by a factor of three, and those keep BDCSVD (the plate tests' and benchmark's campaigns run
// without fault; valgrind finds no invalid read there).
Eigen::MatrixXd rightSingularVectors(const Eigen::MatrixXd& a, Eigen::VectorXd& singular) {
  constexpr Eigen::Index kJacobiColumns = 64;
  if (a.cols() <= kJacobiColumns) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
    singular = svd.singularValues();
    return svd.matrixV();
  }
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  singular = svd.singularValues();
  return svd.matrixV();
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[static_cast<size_t>(i)] != i) i = parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
  return i;
}

}  // namespace

ObservabilityReport analyseObservability(Eigen::MatrixXd jacobian, const std::vector<std::string>& names,
                                         const Eigen::VectorXd& typical, double tol, int threads) {
  const Eigen::Index n = jacobian.cols();
  if (static_cast<Eigen::Index>(names.size()) != n || typical.size() != n)
    throw InvalidInput("analyseObservability: one name and one typical size per column");
  ObservabilityReport rep;
  rep.names = names;
  if (n == 0) return rep;

  // J = QR with Q orthonormal: R has the column norms of J and, for any column scaling D and
  // column subset, the singular values and right singular vectors of J D. All below works on
  // the small R.
  const Eigen::MatrixXd r = jacobian.rows() > n ? triangularFactor(jacobian, threads) : jacobian;
  const Eigen::VectorXd norms = r.colwise().norm().transpose();
  const double largestEffect = (norms.array() * typical.array().abs()).maxCoeff();
  std::vector<Eigen::Index> active;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!(norms[j] * std::abs(typical[j]) > tol * largestEffect))
      rep.noEffect.push_back(names[static_cast<size_t>(j)]);
    else
      active.push_back(j);
  }
  Eigen::MatrixXd scaled(r.rows(), static_cast<Eigen::Index>(active.size()));
  for (size_t k = 0; k < active.size(); ++k) scaled.col(static_cast<Eigen::Index>(k)) = r.col(active[k]) / norms[active[k]];

  Eigen::VectorXd sv;
  const Eigen::MatrixXd v = active.empty() ? Eigen::MatrixXd() : rightSingularVectors(scaled, sv);
  rep.singularValues = Eigen::VectorXd::Zero(n);
  rep.singularValues.head(sv.size()) = sv;
  rep.singularVectors = Eigen::MatrixXd::Zero(sv.size(), n);
  for (size_t k = 0; k < active.size(); ++k) rep.singularVectors.col(active[k]) = v.row(static_cast<Eigen::Index>(k)).head(sv.size()).transpose();
  const double largest = sv.size() ? sv[0] : 0.0;
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (sv[i] > tol * largest) rep.rank = static_cast<int>(i + 1);
  rep.condition = rep.rank > 0 ? largest / sv[rep.rank - 1] : 0.0;

  // Parameters taking part in the same null vector cannot be separated from each other.
  const auto m = static_cast<Eigen::Index>(active.size());
  std::vector<int> parent(static_cast<size_t>(m));
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> inNull(static_cast<size_t>(m), false);
  for (Eigen::Index c = rep.rank; c < m; ++c) {
    int first = -1;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (std::abs(v(j, c)) < 1e-3) continue;  // below: numerical mixing, not participation
      inNull[static_cast<size_t>(j)] = true;
      if (first < 0) first = static_cast<int>(j);
      else parent[static_cast<size_t>(findRoot(parent, static_cast<int>(j)))] = findRoot(parent, first);
    }
  }
  for (Eigen::Index root = 0; root < m; ++root) {
    if (!inNull[static_cast<size_t>(root)] || findRoot(parent, static_cast<int>(root)) != root) continue;
    std::vector<Eigen::Index> members;
    for (Eigen::Index j = 0; j < m; ++j)
      if (inNull[static_cast<size_t>(j)] && findRoot(parent, static_cast<int>(j)) == root) members.push_back(j);
    ParameterGroup g;
    Eigen::MatrixXd sub(r.rows(), static_cast<Eigen::Index>(members.size()));
    for (size_t k = 0; k < members.size(); ++k) {
      const Eigen::Index column = active[static_cast<size_t>(members[k])];
      g.names.push_back(names[static_cast<size_t>(column)]);
      sub.col(static_cast<Eigen::Index>(k)) = r.col(column) / norms[column];
    }
    Eigen::VectorXd subSv;
    const Eigen::MatrixXd subV = rightSingularVectors(sub, subSv);
    for (Eigen::Index c = 0; c < subSv.size(); ++c) {
      if (subSv[c] <= tol * largest) continue;
      // v^T (norm_j p_j): back to the physical parameters.
      std::vector<double> coef(members.size());
      double big = 0;
      for (size_t k = 0; k < members.size(); ++k) {
        coef[k] = subV(static_cast<Eigen::Index>(k), c) * norms[active[static_cast<size_t>(members[k])]];
        if (std::abs(coef[k]) > std::abs(big)) big = coef[k];
      }
      for (auto& x : coef) x /= big;
      g.observable.push_back(coef);
    }
    rep.groups.push_back(std::move(g));
  }
  return rep;
}

std::vector<std::string> ObservabilityReport::findings(const std::string& scope) const {
  std::vector<std::string> out;
  for (const auto& n : noEffect) out.push_back(n + " has no effect on " + scope);
  for (const auto& g : groups) {
    std::string list;
    for (size_t k = 0; k < g.names.size(); ++k)
      list += (k == 0 ? "" : (k + 1 == g.names.size() ? " and " : ", ")) + g.names[k];
    std::string combos;
    bool scaled = false;  // a coefficient other than +-1: its meaning depends on the units
    if (g.names.size() <= 4) {
      for (const auto& c : g.observable) {
        std::string term;
        for (size_t k = 0; k < c.size(); ++k) {
          if (std::abs(c[k]) < 1e-9) continue;
          const double a = std::abs(c[k]);
          const std::string magnitude = std::abs(a - 1.0) < 1e-9 ? "" : fmt::format("{:.4g} ", a);
          scaled = scaled || !magnitude.empty();
          term += term.empty() ? (c[k] < 0 ? "-" : "") + magnitude + g.names[k]
                               : fmt::format(" {} {}{}", c[k] < 0 ? "-" : "+", magnitude, g.names[k]);
        }
        combos += (combos.empty() ? "" : "; ") + term;
      }
    } else {
      combos = fmt::format("{} combinations of the {}", g.observable.size(), g.names.size());
    }
    const bool alike = g.names.size() == 2 && g.observable.size() == 1;
    out.push_back(list + (alike ? " act alike" : " cannot be separated") +
                  (combos.empty() ? ": none of them is observable" : ": only " + combos + " observable") +
                  (scaled ? " (lengths in mm, angles in rad)" : ""));
  }
  return out;
}

IdentifiableColumns proposeIdentifiableColumns(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& typical,
                                               Eigen::Index firstAlwaysKept, double tol) {
  const Eigen::Index rows = jacobian.rows();
  Eigen::MatrixXd candidates = jacobian.leftCols(firstAlwaysKept) * typical.head(firstAlwaysKept).asDiagonal();
  if (jacobian.cols() > firstAlwaysKept) {
    const Eigen::MatrixXd always = jacobian.rightCols(jacobian.cols() - firstAlwaysKept) *
                                   typical.tail(jacobian.cols() - firstAlwaysKept).asDiagonal();
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(always);
    qr.setThreshold(tol);
    const Eigen::MatrixXd q = Eigen::MatrixXd(qr.householderQ()).leftCols(qr.rank());
    candidates -= q * (q.transpose() * candidates);
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(candidates);
  // Relative to the largest column of the scaled Jacobian, not of what the set-up leaves of it:
  // a column the set-up unknowns absorb is dropped.
  const double largest = (jacobian * typical.asDiagonal()).colwise().norm().maxCoeff();
  qr.setThreshold(tol * largest / std::max(qr.maxPivot(), std::numeric_limits<double>::min()));
  IdentifiableColumns out;
  const auto& order = qr.colsPermutation().indices();
  for (Eigen::Index i = 0; i < firstAlwaysKept; ++i) (i < qr.rank() ? out.kept : out.dropped).push_back(order[i]);
  std::sort(out.kept.begin(), out.kept.end());
  std::sort(out.dropped.begin(), out.dropped.end());
  Eigen::MatrixXd kept(rows, static_cast<Eigen::Index>(out.kept.size())), dropped(rows, static_cast<Eigen::Index>(out.dropped.size()));
  for (size_t k = 0; k < out.kept.size(); ++k) kept.col(static_cast<Eigen::Index>(k)) = candidates.col(out.kept[k]);
  for (size_t d = 0; d < out.dropped.size(); ++d) dropped.col(static_cast<Eigen::Index>(d)) = candidates.col(out.dropped[d]);
  // In the scaled columns, where below 1e-6 is rounding; then back to the columns' own units
  // (p_k / t_k stands for ... p_d / t_d).
  out.standsFor = kept.cols() > 0 ? Eigen::MatrixXd(kept.colPivHouseholderQr().solve(dropped))
                                  : Eigen::MatrixXd::Zero(0, dropped.cols());
  for (Eigen::Index k = 0; k < out.standsFor.rows(); ++k)
    for (Eigen::Index d = 0; d < out.standsFor.cols(); ++d) {
      double& c = out.standsFor(k, d);
      c = std::abs(c) > 1e-6 ? c * typical[out.kept[static_cast<size_t>(k)]] / typical[out.dropped[static_cast<size_t>(d)]] : 0.0;
    }
  return out;
}

}  // namespace mtacc
