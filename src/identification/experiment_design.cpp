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

// The small matrices of a trial: 3 x 3 (blocks of three readings: an R-test's or a probe's pose),
// at most 8 x 8 without allocating, or any size (a run's information factor).
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 8, 8>;
constexpr Eigen::Index kSmallRows = 8;

// The criterion after adding a candidate, or swapping one for another, scored from the current M
// without refactorising it (A = M^-1, B_c = X_c A X_c^T, P_c = (I + B_c)^-1, C = X_in A X_out^T):
// D by the determinant lemma, log det M' - log det M = log det(I + B_in) + log det(I - B_out +
// C^T P_in C) (on the nuisance block too for D_s); A and I by Woodbury, trace(W M'^-1) = trace(W A)
// - trace(P_in E_in) - trace(Y (Q E_in Q^T - Q F - (Q F)^T + E_out)) with E_c = X_c A W A X_c^T,
// F = X_in A W A X_out^T, Q = C^T P_in, Y = (B_out - I - Q C)^-1. Every candidate's X A (and
// X A W A) is one product and its own terms are computed here, so that a trial costs only the
// small products between two candidates' rows.
// The log det of a symmetric matrix that must be positive definite (a change that keeps M
// regular); -inf when it is not.
template <class Small>
double logDetOfPositive(const Small& k) {
  const Eigen::LLT<Small> llt(k);
  if (llt.info() != Eigen::Success) return -kInfinity;
  const auto d = llt.matrixLLT().diagonal();
  if (!(d.minCoeff() > 0)) return -kInfinity;
  const double product = d.prod();  // one logarithm where the product neither overflows nor underflows
  return std::isnormal(product) ? 2 * std::log(product) : 2 * d.array().log().sum();
}

template <class Small>
class TrialScores {
 public:
  TrialScores(const Stacked& s, const Eigen::MatrixXd& m, DesignCriterion criterion, const std::vector<int>& nuisance,
              const Eigen::MatrixXd& weight)
      : s_(s), criterion_(criterion), current_(designCriterion(m, criterion, nuisance, weight)) {
    const Eigen::Index p = m.rows();
    const Eigen::MatrixXd inverse = m.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    g_.noalias() = s.rows * inverse;
    own_ = ownTerms(g_, s.rows);
    if (criterion == DesignCriterion::D) {
      if (!nuisance.empty()) {
        const Eigen::MatrixXd mnn = submatrix(m, nuisance);
        gn_.noalias() = s.nuisanceRows * mnn.ldlt().solve(Eigen::MatrixXd::Identity(mnn.rows(), mnn.rows()));
        ownNuisance_ = ownTerms(gn_, s.nuisanceRows);
      }
    } else {
      h_.noalias() = g_ * criterionWeight(p, criterion, nuisance, weight) * inverse;
      for (size_t c = 0; c < s.size.size(); ++c) {
        Own& o = own_[c];
        o.e.noalias() = h_.middleRows(s.first[c], s.size[c]) * s.block(c).transpose();
        o.traceWithE = (o.inverse * o.e).trace();
      }
    }
  }

  double current() const { return current_; }

  double added(size_t in) const {
    const Own& i = own_[in];
    if (criterion_ == DesignCriterion::D) {
      const double change = i.logDet - (gn_.size() > 0 ? ownNuisance_[in].logDet : 0.0);
      return std::isfinite(change) ? current_ + change : -kInfinity;
    }
    const double next = current_ - i.traceWithE;
    return next > 0 ? next : kInfinity;  // a sum of variances is positive
  }

  // The products of every candidate's rows with the rows of `out`, for the swaps of `out`.
  void focus(size_t out) {
    focus_ = out;
    const auto xOut = s_.block(out);
    cOut_.noalias() = g_ * xOut.transpose();
    if (gn_.size() > 0) cnOut_.noalias() = gn_ * s_.nuisanceBlock(out).transpose();
    if (h_.size() > 0) fOut_.noalias() = h_ * xOut.transpose();
  }

  // The criterion with `in` in place of the focused candidate.
  double swapped(size_t in) const {
    if (criterion_ == DesignCriterion::D) {
      double change = swapLogDet(cOut_, own_, in);
      if (gn_.size() > 0 && std::isfinite(change)) change -= swapLogDet(cnOut_, ownNuisance_, in);
      return std::isfinite(change) ? current_ + change : -kInfinity;
    }
    const Own& i = own_[in];
    const Own& o = own_[focus_];
    const auto c = cOut_.middleRows(s_.first[in], s_.size[in]);
    const auto f = fOut_.middleRows(s_.first[in], s_.size[in]);
    Small q, qf, schur, inner;
    q.noalias() = c.transpose() * i.inverse;
    schur = o.b;
    schur.diagonal().array() -= 1.0;
    schur.noalias() -= q * c;
    const Eigen::PartialPivLU<Small> lu(schur);
    if (!(std::abs(lu.determinant()) > 1e-300)) return kInfinity;
    qf.noalias() = q * f;
    inner.noalias() = q * i.e * q.transpose();
    inner -= qf + qf.transpose();
    inner += o.e;
    const double next = current_ - i.traceWithE - lu.solve(inner).trace();
    return next > 0 ? next : kInfinity;
  }

 private:
  struct Own {
    Small b, inverse, e;  // B_c, (I + B_c)^-1, E_c
    double logDet = 0, traceWithE = 0;  // log det(I + B_c), trace(P_c E_c)
  };

  std::vector<Own> ownTerms(const Eigen::MatrixXd& g, const Eigen::MatrixXd& rows) const {
    std::vector<Own> out(s_.size.size());
    for (size_t c = 0; c < out.size(); ++c) {
      Own& o = out[c];
      o.b.noalias() = g.middleRows(s_.first[c], s_.size[c]) * rows.middleRows(s_.first[c], s_.size[c]).transpose();
      Small k = o.b;
      k.diagonal().array() += 1.0;
      const Eigen::LLT<Small> llt(k);
      o.logDet = logDetOfPositive(k);
      o.inverse = llt.solve(Small::Identity(k.rows(), k.rows()));
    }
    return out;
  }

  // log det(I + B_in) + log det(I - B_out + C^T P_in C), C from the focused products.
  double swapLogDet(const Eigen::MatrixXd& cOut, const std::vector<Own>& own, size_t in) const {
    const Own& i = own[in];
    if (!std::isfinite(i.logDet)) return -kInfinity;
    const auto c = cOut.middleRows(s_.first[in], s_.size[in]);
    Small k = -own[focus_].b;
    k.diagonal().array() += 1.0;
    k.noalias() += c.transpose() * i.inverse * c;
    return i.logDet + logDetOfPositive(k);
  }

  const Stacked& s_;
  DesignCriterion criterion_;
  double current_;
  Eigen::MatrixXd g_, gn_, h_;  // X M^-1, X_n M_nn^-1, X M^-1 W M^-1
  std::vector<Own> own_, ownNuisance_;
  size_t focus_ = 0;
  Eigen::MatrixXd cOut_, cnOut_, fOut_;  // g_, gn_, h_ times the focused candidate's rows
};

// What the chosen candidates cost: their own costs and each group's once.
class Costs {
 public:
  explicit Costs(const DesignOptions& o) : o_(o), used_(o.groupCost.size()) {}
  bool budgeted() const { return o_.budget > 0; }
  // The cost of the chosen candidates, with candidate `in` added (>= 0) and the one at position
  // `skip` of `chosen` left out (>= 0): a trial's cost without copying the design.
  double of(const std::vector<int>& chosen, int in = -1, long skip = -1) const {
    std::fill(used_.begin(), used_.end(), false);
    double total = 0;
    const auto add = [&](int c) {
      total += o_.cost[static_cast<size_t>(c)];
      if (o_.groups.empty()) return;
      for (const int g : o_.groups[static_cast<size_t>(c)])
        if (!used_[static_cast<size_t>(g)]) {
          used_[static_cast<size_t>(g)] = true;
          total += o_.groupCost[static_cast<size_t>(g)];
        }
    };
    for (size_t k = 0; k < chosen.size(); ++k)
      if (static_cast<long>(k) != skip) add(chosen[k]);
    if (in >= 0) add(in);
    return total;
  }
  bool fits(double cost) const { return cost <= o_.budget * (1 + 1e-12); }

 private:
  const DesignOptions& o_;
  mutable std::vector<char> used_;  // scratch: the groups already paid for
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

namespace {

template <class Small>
Design exchange(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o, const Stacked& s) {
  const Eigen::Index p = candidates.front().cols();
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
      const TrialScores<Small> t(s, sum(chosen) + ridge, DesignCriterion::D, {}, {});
      const double before = costs.budgeted() ? costs.of(chosen) : 0;
      int best = -1;
      double bestValue = -kInfinity;
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (!allowed(chosen, c) || inGroup(c, without)) continue;
        double value = t.added(c) - t.current();
        if (costs.budgeted()) {
          const double after = costs.of(chosen, static_cast<int>(c));
          if (!costs.fits(after)) continue;
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
    TrialScores<Small> t(s, m, o.criterion, o.nuisance, o.weight);
    double bestValue = current;
    int bestOut = -1, bestIn = -1;
    for (size_t k = 0; k < d.chosen.size(); ++k) {
      const auto out = static_cast<size_t>(d.chosen[k]);
      t.focus(out);
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (c == out || !allowed(d.chosen, c)) continue;
        if (costs.budgeted() && !costs.fits(costs.of(d.chosen, static_cast<int>(c), static_cast<long>(k)))) continue;
        const double value = t.swapped(c);
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

}  // namespace

Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& o) {
  checkOptions(candidates, o);
  const Stacked s = stack(candidates, o.nuisance);
  const auto [fewest, most] = std::minmax_element(s.size.begin(), s.size.end());
  if (*fewest == 3 && *most == 3) return exchange<Eigen::Matrix3d>(candidates, o, s);  // R-test and probe poses
  return *most <= kSmallRows ? exchange<SmallMatrix>(candidates, o, s) : exchange<Eigen::MatrixXd>(candidates, o, s);
}

}  // namespace mtacc
