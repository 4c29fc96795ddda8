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

// The criterion's change when the rows `add` join M and the rows `drop` leave it, from M^-1 only:
// det(M') / det(M) = det(I + S U M^-1 U^T) and, by Woodbury, trace(M'^-1) = trace(M^-1) -
// trace((S + U M^-1 U^T)^-1 U M^-2 U^T), U = [add; drop], S = diag(I, -I). Returns the new
// criterion, or the worst value when M' is singular.
double changedCriterion(const Eigen::MatrixXd& inverse, const Eigen::MatrixXd& inverseSquared, double current,
                        const Eigen::MatrixXd& add, const Eigen::MatrixXd* drop, DesignCriterion criterion) {
  const Eigen::Index ka = add.rows(), kd = drop ? drop->rows() : 0;
  Eigen::MatrixXd u(ka + kd, add.cols());
  u.topRows(ka) = add;
  if (drop) u.bottomRows(kd) = *drop;
  Eigen::VectorXd sign = Eigen::VectorXd::Ones(ka + kd);
  sign.tail(kd).setConstant(-1.0);
  const Eigen::MatrixXd g = u * inverse * u.transpose();
  if (criterion == DesignCriterion::D) {
    const Eigen::MatrixXd k = Eigen::MatrixXd::Identity(ka + kd, ka + kd) + sign.asDiagonal() * g;
    const double det = k.determinant();
    return det > 0 ? current + std::log(det) : -kInfinity;
  }
  const Eigen::MatrixXd inner = Eigen::MatrixXd(sign.asDiagonal()) + g;  // S^-1 = S
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(inner);
  if (!lu.isInvertible()) return kInfinity;
  const double reduction = lu.solve(u * inverseSquared * u.transpose()).trace();
  const double next = current - reduction;
  return next > 0 ? next : kInfinity;  // a trace of a positive definite inverse is positive
}

bool better(double a, double b, DesignCriterion criterion) {
  return criterion == DesignCriterion::D ? a > b * (1 + 1e-12) + 1e-12 : a < b * (1 - 1e-12) - 1e-300;
}

}  // namespace

const char* toString(DesignCriterion criterion) { return criterion == DesignCriterion::D ? "D" : "A"; }

double designCriterion(const Eigen::MatrixXd& information, DesignCriterion criterion) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD();
  const double scale = information.diagonal().cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-13 * scale))
    return criterion == DesignCriterion::D ? -kInfinity : kInfinity;
  if (criterion == DesignCriterion::D) return d.array().log().sum();
  return ldlt.solve(Eigen::MatrixXd::Identity(information.rows(), information.cols())).trace();
}

Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o) {
  if (candidates.empty()) throw InvalidInput("experiment design: no candidates");
  const Eigen::Index p = candidates.front().cols();
  for (const auto& c : candidates)
    if (c.cols() != p || c.rows() == 0) throw InvalidInput("experiment design: every candidate needs readings on the same parameters");
  if (o.count < 1) throw InvalidInput("experiment design: choose at least one candidate");
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(p, p);
  for (const auto& c : candidates) all.noalias() += c.transpose() * c;
  if (designCriterion(all, DesignCriterion::D) == -kInfinity)
    throw InvalidInput("experiment design: the candidates together cannot determine every parameter (their information is singular)");
  const auto sum = [&](const std::vector<int>& chosen) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(p, p);
    for (int i : chosen) m.noalias() += candidates[static_cast<size_t>(i)].transpose() * candidates[static_cast<size_t>(i)];
    return m;
  };
  // Greedy start on the ridged matrix (the D-criterion's gain is defined before full rank).
  Design d;
  Eigen::MatrixXd m = o.ridge * all.diagonal().maxCoeff() * Eigen::MatrixXd::Identity(p, p);
  for (int step = 0; step < o.count; ++step) {
    const Eigen::MatrixXd inverse = m.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    const double current = designCriterion(m, DesignCriterion::D);
    int best = -1;
    double bestValue = -kInfinity;
    for (size_t c = 0; c < candidates.size(); ++c) {
      const double value = changedCriterion(inverse, inverse, current, candidates[c], nullptr, DesignCriterion::D);
      if (value > bestValue) {
        bestValue = value;
        best = static_cast<int>(c);
      }
    }
    d.chosen.push_back(best);
    m.noalias() += candidates[static_cast<size_t>(best)].transpose() * candidates[static_cast<size_t>(best)];
  }
  m = sum(d.chosen);
  double current = designCriterion(m, o.criterion);
  if (!std::isfinite(current))
    throw InvalidInput(fmt::format("experiment design: {} readings cannot determine the {} parameters; choose more", o.count, p));
  // Fedorov's exchange: the best improving swap, until none improves.
  while (d.exchanges < o.maxExchanges) {
    const Eigen::MatrixXd inverse = m.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    const Eigen::MatrixXd inverseSquared = inverse * inverse;
    double bestValue = current;
    int bestOut = -1, bestIn = -1;
    for (size_t k = 0; k < d.chosen.size(); ++k) {
      const auto& out = candidates[static_cast<size_t>(d.chosen[k])];
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (static_cast<int>(c) == d.chosen[k]) continue;
        const double value = changedCriterion(inverse, inverseSquared, current, candidates[c], &out, o.criterion);
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
    current = designCriterion(m, o.criterion);
    ++d.exchanges;
  }
  std::sort(d.chosen.begin(), d.chosen.end());
  d.criterion = current;
  d.information = m;
  return d;
}

}  // namespace mtacc
