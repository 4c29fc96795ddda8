#include "mtacc/identification/experiment_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

double worst(DesignCriterion criterion) { return criterion == DesignCriterion::D ? -kInfinity : kInfinity; }

bool better(double a, double b, DesignCriterion criterion) {
  return criterion == DesignCriterion::D ? a > b * (1 + 1e-12) + 1e-12 : a < b * (1 - 1e-12) - 1e-300;
}

Eigen::MatrixXd submatrix(const Eigen::MatrixXd& m, const std::vector<int>& index) {
  const auto n = static_cast<Eigen::Index>(index.size());
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b) out(a, b) = m(index[static_cast<size_t>(a)], index[static_cast<size_t>(b)]);
  return out;
}

// The weight W of trace(W M^-1): the interest columns' identity (A), the given one (I).
Eigen::MatrixXd criterionWeight(Eigen::Index p, DesignCriterion criterion, const std::vector<int>& nuisance, const Eigen::MatrixXd& weight) {
  if (criterion == DesignCriterion::I) return weight;
  Eigen::VectorXd interest = Eigen::VectorXd::Ones(p);
  for (int j : nuisance) interest[j] = 0;
  return interest.asDiagonal();
}

// Every candidate's rows stacked, candidate c the rows first[c] .. first[c] + size[c].
struct Stacked {
  Eigen::MatrixXd rows, nuisanceRows;
  std::vector<Eigen::Index> first, size;
  auto block(size_t c) const { return rows.middleRows(first[c], size[c]); }
  auto nuisanceBlock(size_t c) const { return nuisanceRows.middleRows(first[c], size[c]); }
};

Stacked stack(const std::vector<Eigen::MatrixXd>& candidates, const std::vector<int>& nuisance) {
  Stacked s;
  Eigen::Index total = 0;
  for (const auto& c : candidates) {
    s.first.push_back(total);
    s.size.push_back(c.rows());
    total += c.rows();
  }
  s.rows.resize(total, candidates.front().cols());
  for (size_t c = 0; c < candidates.size(); ++c) s.rows.middleRows(s.first[c], s.size[c]) = candidates[c];
  s.nuisanceRows.resize(total, static_cast<Eigen::Index>(nuisance.size()));
  for (size_t j = 0; j < nuisance.size(); ++j) s.nuisanceRows.col(static_cast<Eigen::Index>(j)) = s.rows.col(nuisance[j]);
  return s;
}

// The criterion after adding a candidate, or swapping one, scored from the current M by the
// determinant lemma (D: log det(I + S U M^-1 U^T), U the rows added and dropped, S = diag(I, -I); on
// the nuisance block too for D_s) and Woodbury (A, I: trace(W M'^-1) = trace(W M^-1) - trace((S +
// U M^-1 U^T)^-1 U M^-1 W M^-1 U^T)). Every candidate's X M^-1 (and X M^-1 W M^-1) is one product
// computed here, so that a trial costs only the small products between two candidates' rows.
class TrialScores {
 public:
  TrialScores(const Stacked& s, const Eigen::MatrixXd& m, DesignCriterion criterion, const std::vector<int>& nuisance,
              const Eigen::MatrixXd& weight)
      : s_(s), criterion_(criterion), current_(designCriterion(m, criterion, nuisance, weight)) {
    const Eigen::Index p = m.rows();
    const Eigen::MatrixXd inverse = m.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    g_.noalias() = s.rows * inverse;
    if (criterion == DesignCriterion::D) {
      if (!nuisance.empty()) {
        const Eigen::MatrixXd mnn = submatrix(m, nuisance);
        gn_.noalias() = s.nuisanceRows * mnn.ldlt().solve(Eigen::MatrixXd::Identity(mnn.rows(), mnn.rows()));
      }
    } else {
      h_.noalias() = g_ * criterionWeight(p, criterion, nuisance, weight) * inverse;
    }
  }

  double current() const { return current_; }
  double added(size_t c) const { return score(c, nullptr); }
  double swapped(size_t out, size_t in) const { return score(in, &out); }

 private:
  // (r_in + r_out) square: block (a, b) = sign_a * delta_ab * I + X_a P X_b^T, P X_b^T from `prod`.
  static void lowRank(const Eigen::MatrixXd& prod, const Eigen::MatrixXd& rows, const Stacked& s, size_t in, const size_t* out,
                      bool signOnDiagonal, bool signOnRows, Eigen::MatrixXd& k) {
    const Eigen::Index ri = s.size[in], ro = out ? s.size[*out] : 0;
    k.resize(ri + ro, ri + ro);
    const auto pi = prod.middleRows(s.first[in], ri), xi = rows.middleRows(s.first[in], ri);
    k.topLeftCorner(ri, ri).noalias() = pi * xi.transpose();
    if (out) {
      const auto po = prod.middleRows(s.first[*out], ro), xo = rows.middleRows(s.first[*out], ro);
      k.topRightCorner(ri, ro).noalias() = pi * xo.transpose();
      k.bottomLeftCorner(ro, ri).noalias() = po * xi.transpose();
      k.bottomRightCorner(ro, ro).noalias() = po * xo.transpose();
      if (signOnRows) k.bottomRows(ro) *= -1.0;
    }
    if (signOnDiagonal) {
      k.diagonal().head(ri).array() += 1.0;
      k.diagonal().tail(ro).array() += signOnRows ? 1.0 : -1.0;
    }
  }

  static double logDet(const Eigen::MatrixXd& k) {
    const double det = Eigen::PartialPivLU<Eigen::MatrixXd>(k).determinant();
    return det > 0 ? std::log(det) : -kInfinity;
  }

  double score(size_t in, const size_t* out) const {
    if (criterion_ == DesignCriterion::D) {
      lowRank(g_, s_.rows, s_, in, out, true, true, k_);
      double change = logDet(k_);
      if (gn_.size() > 0 && std::isfinite(change)) {
        lowRank(gn_, s_.nuisanceRows, s_, in, out, true, true, k_);
        change -= logDet(k_);
      }
      return std::isfinite(change) ? current_ + change : -kInfinity;
    }
    lowRank(g_, s_.rows, s_, in, out, true, false, k_);
    lowRank(h_, s_.rows, s_, in, out, false, false, rhs_);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(k_);
    if (!(std::abs(lu.determinant()) > 1e-300)) return kInfinity;
    const double next = current_ - lu.solve(rhs_).trace();
    return next > 0 ? next : kInfinity;  // a sum of variances is positive
  }

  const Stacked& s_;
  DesignCriterion criterion_;
  double current_;
  Eigen::MatrixXd g_, gn_, h_;  // X M^-1, X_n M_nn^-1, X M^-1 W M^-1
  mutable Eigen::MatrixXd k_, rhs_;
};

// What the chosen candidates cost: their own costs and each group's once.
class Costs {
 public:
  explicit Costs(const DesignOptions& o) : o_(o) {}
  bool budgeted() const { return o_.budget > 0; }
  double of(const std::vector<int>& chosen) const {
    double total = 0;
    std::vector<bool> used(o_.groupCost.size(), false);
    for (int c : chosen) {
      total += o_.cost[static_cast<size_t>(c)];
      if (o_.groups.empty()) continue;
      for (const int g : o_.groups[static_cast<size_t>(c)])
        if (!used[static_cast<size_t>(g)]) {
          used[static_cast<size_t>(g)] = true;
          total += o_.groupCost[static_cast<size_t>(g)];
        }
    }
    return total;
  }
  bool fits(const std::vector<int>& chosen) const { return of(chosen) <= o_.budget * (1 + 1e-12); }

 private:
  const DesignOptions& o_;
};

void checkOptions(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o) {
  if (candidates.empty()) throw InvalidInput("experiment design: no candidates");
  const Eigen::Index p = candidates.front().cols();
  for (const auto& c : candidates)
    if (c.cols() != p || c.rows() == 0) throw InvalidInput("experiment design: every candidate needs readings on the same parameters");
  for (int j : o.nuisance)
    if (j < 0 || j >= p) throw InvalidInput("experiment design: a nuisance column beyond the parameters");
  if (!o.nuisance.empty() && !(o.nuisancePrior >= 0)) throw InvalidInput("experiment design: the nuisance prior must not be negative");
  if (o.criterion == DesignCriterion::I && (o.weight.rows() != p || o.weight.cols() != p))
    throw InvalidInput("experiment design: the I criterion needs a weight over the parameters");
  if (o.budget > 0) {
    const auto n = candidates.size();
    if (o.cost.size() != n || (!o.groups.empty() && o.groups.size() != n))
      throw InvalidInput("experiment design: a budget needs a cost (and its groups, if any) per candidate");
    for (size_t c = 0; c < n; ++c) {
      if (!(o.cost[c] > 0) || !std::isfinite(o.cost[c])) throw InvalidInput("experiment design: every cost must be positive");
      if (!o.groups.empty())
        for (const int g : o.groups[c])
          if (g < 0 || g >= static_cast<int>(o.groupCost.size())) throw InvalidInput("experiment design: a group without its cost");
    }
    for (const double g : o.groupCost)
      if (!(g >= 0) || !std::isfinite(g)) throw InvalidInput("experiment design: a group's cost must be finite and not negative");
  } else if (o.count < 1) {
    throw InvalidInput("experiment design: choose at least one candidate");
  }
}

bool isChosen(const std::vector<int>& chosen, size_t c) { return std::find(chosen.begin(), chosen.end(), static_cast<int>(c)) != chosen.end(); }

}  // namespace

const char* toString(DesignCriterion criterion) {
  switch (criterion) {
    case DesignCriterion::A:
      return "A";
    case DesignCriterion::I:
      return "I";
    case DesignCriterion::D:
      break;
  }
  return "D";
}

double designCriterion(const Eigen::MatrixXd& information, DesignCriterion criterion, const std::vector<int>& nuisance,
                       const Eigen::MatrixXd& weight) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD();
  const double scale = information.diagonal().cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-13 * scale)) return worst(criterion);
  if (criterion == DesignCriterion::D) {
    double logDet = d.array().log().sum();
    if (!nuisance.empty()) logDet -= submatrix(information, nuisance).ldlt().vectorD().array().log().sum();
    return logDet;
  }
  const Eigen::MatrixXd inverse = ldlt.solve(Eigen::MatrixXd::Identity(information.rows(), information.cols()));
  return (criterionWeight(information.rows(), criterion, nuisance, weight) * inverse).trace();
}

Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o) {
  checkOptions(candidates, o);
  const Eigen::Index p = candidates.front().cols();
  const Stacked s = stack(candidates, o.nuisance);
  const Costs costs(o);
  Eigen::MatrixXd prior = Eigen::MatrixXd::Zero(p, p);
  for (int j : o.nuisance) prior(j, j) = o.nuisancePrior;
  if (designCriterion(s.rows.transpose() * s.rows + prior, DesignCriterion::D) == -kInfinity)
    throw InvalidInput("experiment design: the candidates together cannot determine every parameter (their information is singular)");
  const auto sum = [&](const std::vector<int>& chosen) {
    Eigen::MatrixXd m = prior;
    for (int i : chosen) m.noalias() += s.block(static_cast<size_t>(i)).transpose() * s.block(static_cast<size_t>(i));
    return m;
  };
  const auto allowed = [&](const std::vector<int>& chosen, size_t c) { return o.repeats || !isChosen(chosen, c); };

  const auto inGroup = [&](size_t c, int g) {
    return !o.groups.empty() && std::find(o.groups[c].begin(), o.groups[c].end(), g) != o.groups[c].end();
  };
  // Adds the best candidate (with a budget: the best gain per cost that still fits) until the count
  // is reached or nothing fits; none of group `without`. The gain is D's on the ridged matrix,
  // defined before M has full rank.
  const Eigen::MatrixXd ridge = o.ridge * (s.rows.colwise().squaredNorm().maxCoeff() + prior.diagonal().maxCoeff()) *
                                Eigen::MatrixXd::Identity(p, p);
  const auto addGreedily = [&](std::vector<int>& chosen, int without) {
    for (;;) {
      if (!costs.budgeted() && static_cast<int>(chosen.size()) >= o.count) return;
      const TrialScores t(s, sum(chosen) + ridge, DesignCriterion::D, {}, {});
      const double before = costs.budgeted() ? costs.of(chosen) : 0;
      int best = -1;
      double bestValue = -kInfinity;
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (!allowed(chosen, c) || inGroup(c, without)) continue;
        double value = t.added(c) - t.current();
        if (costs.budgeted()) {
          chosen.push_back(static_cast<int>(c));
          const double after = costs.of(chosen);
          const bool fits = costs.fits(chosen);
          chosen.pop_back();
          if (!fits) continue;
          value /= after - before;
        }
        if (value > bestValue) {
          bestValue = value;
          best = static_cast<int>(c);
        }
      }
      if (best < 0) return;
      chosen.push_back(best);
    }
  };
  Design d;
  addGreedily(d.chosen, -1);
  Eigen::MatrixXd m = sum(d.chosen);
  double current = designCriterion(m, o.criterion, o.nuisance, o.weight);
  if (!std::isfinite(current)) {
    if (costs.budgeted())
      throw InvalidInput(fmt::format("experiment design: the budget {:g} fits {} candidates, too few to determine the {} parameters", o.budget,
                                     d.chosen.size(), p));
    throw InvalidInput(fmt::format("experiment design: {} readings cannot determine the {} parameters; choose more", o.count, p));
  }
  // With a budget and groups, a move larger than a swap: a group given up (its chosen candidates
  // dropped, a set-up not made) and the time it frees refilled from the others; the best, if it
  // improves.
  const auto bestRegrouping = [&]() -> std::optional<std::vector<int>> {
    std::optional<std::vector<int>> best;
    double bestValue = current;
    for (size_t g = 0; g < o.groupCost.size(); ++g) {
      std::vector<int> trial;
      for (int c : d.chosen)
        if (!inGroup(static_cast<size_t>(c), static_cast<int>(g))) trial.push_back(c);
      if (trial.size() == d.chosen.size()) continue;
      addGreedily(trial, static_cast<int>(g));
      const double value = designCriterion(sum(trial), o.criterion, o.nuisance, o.weight);
      if (better(value, bestValue, o.criterion)) {
        bestValue = value;
        best = std::move(trial);
      }
    }
    return best;
  };
  // Fedorov's exchange: the best improving swap (within the budget), then whatever now fits; when no
  // swap improves, the best regrouping; until neither improves.
  while (d.exchanges < o.maxExchanges) {
    const TrialScores t(s, m, o.criterion, o.nuisance, o.weight);
    double bestValue = current;
    int bestOut = -1, bestIn = -1;
    for (size_t k = 0; k < d.chosen.size(); ++k) {
      const auto out = static_cast<size_t>(d.chosen[k]);
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (c == out || !allowed(d.chosen, c)) continue;
        if (costs.budgeted()) {
          std::vector<int> trial = d.chosen;
          trial[k] = static_cast<int>(c);
          if (!costs.fits(trial)) continue;
        }
        const double value = t.swapped(out, c);
        if (better(value, bestValue, o.criterion)) {
          bestValue = value;
          bestOut = static_cast<int>(k);
          bestIn = static_cast<int>(c);
        }
      }
    }
    if (bestOut >= 0) {
      d.chosen[static_cast<size_t>(bestOut)] = bestIn;
      if (costs.budgeted()) addGreedily(d.chosen, -1);
    } else if (auto regrouped = costs.budgeted() ? bestRegrouping() : std::nullopt) {
      d.chosen = std::move(*regrouped);
    } else {
      break;
    }
    m = sum(d.chosen);  // rebuilt, so that no rounding accumulates over the swaps
    current = designCriterion(m, o.criterion, o.nuisance, o.weight);
    ++d.exchanges;
  }
  std::sort(d.chosen.begin(), d.chosen.end());
  d.criterion = current;
  d.information = m;
  if (costs.budgeted()) d.cost = costs.of(d.chosen);
  return d;
}

}  // namespace mtacc
