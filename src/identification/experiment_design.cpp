#include "mtacc/identification/experiment_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// What scores a trial swap, from the current M: M^-1, M^-1 W M^-1 (W selecting the parameters of
// interest) and, with nuisance columns, M_nn^-1.
struct Scoring {
  Eigen::MatrixXd inverse, weighted, nuisanceInverse;
  std::vector<int> nuisance;
  DesignCriterion criterion;
  double current;
};

Scoring scoring(const Eigen::MatrixXd& m, const std::vector<int>& nuisance, DesignCriterion criterion) {
  Scoring s;
  const Eigen::Index p = m.rows();
  s.inverse = m.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
  Eigen::VectorXd interest = Eigen::VectorXd::Ones(p);
  for (int j : nuisance) interest[j] = 0;
  s.weighted = s.inverse * interest.asDiagonal() * s.inverse;
  s.nuisance = nuisance;
  if (!nuisance.empty()) {
    const auto n = static_cast<Eigen::Index>(nuisance.size());
    Eigen::MatrixXd mnn(n, n);
    for (Eigen::Index a = 0; a < n; ++a)
      for (Eigen::Index b = 0; b < n; ++b) mnn(a, b) = m(nuisance[static_cast<size_t>(a)], nuisance[static_cast<size_t>(b)]);
    s.nuisanceInverse = mnn.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  }
  s.criterion = criterion;
  s.current = designCriterion(m, criterion, nuisance);
  return s;
}

// log det(I + S U A U^T): the log of det(M + U^T S U) / det(M) for A = M^-1 (the determinant lemma).
double logDetChange(const Eigen::MatrixXd& u, const Eigen::VectorXd& sign, const Eigen::MatrixXd& a) {
  const Eigen::MatrixXd k = Eigen::MatrixXd::Identity(u.rows(), u.rows()) + sign.asDiagonal() * (u * a * u.transpose());
  const double det = k.determinant();
  return det > 0 ? std::log(det) : -kInfinity;
}

// The criterion when the rows `add` join M and the rows `drop` leave it: D_s by the determinant
// lemma on M and on its nuisance block, A by Woodbury: trace(W M'^-1) = trace(W M^-1) -
// trace((S + U M^-1 U^T)^-1 U M^-1 W M^-1 U^T), U = [add; drop], S = diag(I, -I). The worst value
// when M' is singular.
double changedCriterion(const Scoring& s, const Eigen::MatrixXd& add, const Eigen::MatrixXd* drop) {
  const Eigen::Index ka = add.rows(), kd = drop ? drop->rows() : 0;
  Eigen::MatrixXd u(ka + kd, add.cols());
  u.topRows(ka) = add;
  if (drop) u.bottomRows(kd) = *drop;
  Eigen::VectorXd sign = Eigen::VectorXd::Ones(ka + kd);
  sign.tail(kd).setConstant(-1.0);
  if (s.criterion == DesignCriterion::D) {
    double change = logDetChange(u, sign, s.inverse);
    if (!s.nuisance.empty() && std::isfinite(change)) {
      Eigen::MatrixXd un(u.rows(), static_cast<Eigen::Index>(s.nuisance.size()));
      for (size_t j = 0; j < s.nuisance.size(); ++j) un.col(static_cast<Eigen::Index>(j)) = u.col(s.nuisance[j]);
      change -= logDetChange(un, sign, s.nuisanceInverse);
    }
    return std::isfinite(change) ? s.current + change : -kInfinity;
  }
  const Eigen::MatrixXd inner = Eigen::MatrixXd(sign.asDiagonal()) + u * s.inverse * u.transpose();  // S^-1 = S
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(inner);
  if (!lu.isInvertible()) return kInfinity;
  const double next = s.current - lu.solve(u * s.weighted * u.transpose()).trace();
  return next > 0 ? next : kInfinity;  // a sum of variances is positive
}

bool better(double a, double b, DesignCriterion criterion) {
  return criterion == DesignCriterion::D ? a > b * (1 + 1e-12) + 1e-12 : a < b * (1 - 1e-12) - 1e-300;
}

}  // namespace

const char* toString(DesignCriterion criterion) { return criterion == DesignCriterion::D ? "D" : "A"; }

double designCriterion(const Eigen::MatrixXd& information, DesignCriterion criterion, const std::vector<int>& nuisance) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD();
  const double scale = information.diagonal().cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-13 * scale))
    return criterion == DesignCriterion::D ? -kInfinity : kInfinity;
  std::vector<bool> isNuisance(static_cast<size_t>(information.rows()), false);
  for (int j : nuisance) isNuisance[static_cast<size_t>(j)] = true;
  if (criterion == DesignCriterion::D) {
    double logDet = d.array().log().sum();
    if (!nuisance.empty()) {
      const auto n = static_cast<Eigen::Index>(nuisance.size());
      Eigen::MatrixXd mnn(n, n);
      for (Eigen::Index a = 0; a < n; ++a)
        for (Eigen::Index b = 0; b < n; ++b) mnn(a, b) = information(nuisance[static_cast<size_t>(a)], nuisance[static_cast<size_t>(b)]);
      logDet -= mnn.ldlt().vectorD().array().log().sum();
    }
    return logDet;
  }
  const Eigen::MatrixXd inverse = ldlt.solve(Eigen::MatrixXd::Identity(information.rows(), information.cols()));
  double trace = 0;
  for (Eigen::Index j = 0; j < inverse.rows(); ++j)
    if (!isNuisance[static_cast<size_t>(j)]) trace += inverse(j, j);
  return trace;
}

Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o) {
  if (candidates.empty()) throw InvalidInput("experiment design: no candidates");
  const Eigen::Index p = candidates.front().cols();
  for (const auto& c : candidates)
    if (c.cols() != p || c.rows() == 0) throw InvalidInput("experiment design: every candidate needs readings on the same parameters");
  if (o.count < 1) throw InvalidInput("experiment design: choose at least one candidate");
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(p, p);
  for (const auto& c : candidates) all.noalias() += c.transpose() * c;
  for (int j : o.nuisance) all(j, j) += o.nuisancePrior;
  if (designCriterion(all, DesignCriterion::D) == -kInfinity)
    throw InvalidInput("experiment design: the candidates together cannot determine every parameter (their information is singular)");
  for (int j : o.nuisance)
    if (j < 0 || j >= p) throw InvalidInput("experiment design: a nuisance column beyond the parameters");
  if (!o.nuisance.empty() && !(o.nuisancePrior >= 0)) throw InvalidInput("experiment design: the nuisance prior must not be negative");
  Eigen::MatrixXd prior = Eigen::MatrixXd::Zero(p, p);
  for (int j : o.nuisance) prior(j, j) = o.nuisancePrior;
  const auto sum = [&](const std::vector<int>& chosen) {
    Eigen::MatrixXd m = prior;
    for (int i : chosen) m.noalias() += candidates[static_cast<size_t>(i)].transpose() * candidates[static_cast<size_t>(i)];
    return m;
  };
  // Greedy start on the ridged matrix (the D-criterion's gain is defined before full rank).
  Design d;
  Eigen::MatrixXd m = prior + o.ridge * all.diagonal().maxCoeff() * Eigen::MatrixXd::Identity(p, p);
  for (int step = 0; step < o.count; ++step) {
    const Scoring s = scoring(m, {}, DesignCriterion::D);
    int best = -1;
    double bestValue = -kInfinity;
    for (size_t c = 0; c < candidates.size(); ++c) {
      const double value = changedCriterion(s, candidates[c], nullptr);
      if (value > bestValue) {
        bestValue = value;
        best = static_cast<int>(c);
      }
    }
    d.chosen.push_back(best);
    m.noalias() += candidates[static_cast<size_t>(best)].transpose() * candidates[static_cast<size_t>(best)];
  }
  m = sum(d.chosen);
  double current = designCriterion(m, o.criterion, o.nuisance);
  if (!std::isfinite(current))
    throw InvalidInput(fmt::format("experiment design: {} readings cannot determine the {} parameters; choose more", o.count, p));
  // Fedorov's exchange: the best improving swap, until none improves.
  while (d.exchanges < o.maxExchanges) {
    const Scoring s = scoring(m, o.nuisance, o.criterion);
    double bestValue = current;
    int bestOut = -1, bestIn = -1;
    for (size_t k = 0; k < d.chosen.size(); ++k) {
      const auto& out = candidates[static_cast<size_t>(d.chosen[k])];
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (static_cast<int>(c) == d.chosen[k]) continue;
        const double value = changedCriterion(s, candidates[c], &out);
        if (better(value, bestValue, o.criterion)) {
          bestValue = value;
          bestOut = static_cast<int>(k);
          bestIn = static_cast<int>(c);
        }
      }
    }
    if (bestOut < 0) break;
    d.chosen[static_cast<size_t>(bestOut)] = bestIn;
    m = sum(d.chosen);  // rebuilt, so that no rounding accumulates over the swaps
    current = designCriterion(m, o.criterion, o.nuisance);
    ++d.exchanges;
  }
  std::sort(d.chosen.begin(), d.chosen.end());
  d.criterion = current;
  d.information = m;
  return d;
}

}  // namespace mtacc
