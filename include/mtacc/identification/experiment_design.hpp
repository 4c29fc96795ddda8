#pragma once
// Optimal experimental design over a candidate set: which candidates (a pose of an instrument, each
// giving a block of readings) to measure so that the parameters are best determined. The
// candidates' blocks are rows of the readings' Jacobian, each divided by its reading's noise, so that
// the information matrix of a design is M = sum of J_b^T J_b over its blocks (the inverse of the
// estimates' covariance). D-optimal: the largest log det M (the smallest joint uncertainty);
// A-optimal: the smallest trace M^-1 (the sum of the variances); I-optimal: the smallest trace W M^-1
// for a weight W (the mean variance of a prediction, e.g. of the TCP over a working volume, W the
// mean of its Jacobians' T^T T). A greedy start, then Fedorov's exchange: the best swap of a chosen
// block for a candidate, through the determinant and Woodbury identities of the low-rank change,
// each trial from products precomputed once per swap (X_c M^-1 for every candidate), until no swap
// improves it. Either a number of blocks, or a budget (machine time) that their costs must fit.
#include <vector>

#include <Eigen/Core>

namespace mtacc {

enum class DesignCriterion { D, A, I };
const char* toString(DesignCriterion criterion);

struct DesignOptions {
  DesignCriterion criterion = DesignCriterion::D;
  int count = 0;             // blocks to choose (a candidate may be chosen more than once: a repeat)
  double ridge = 1e-9;       // added to M's diagonal in the greedy start, before M has full rank
  int maxExchanges = 10000;  // swaps at most (each strictly improving)
  // Columns that are nuisance parameters (a set-up's unknowns): they are estimated with the others
  // but the criterion is of the others only — D_s: log det M - log det M_nn (the log det of the
  // others' information once the nuisance is estimated), A: the sum of the others' variances. Each
  // carries a prior information `nuisancePrior` (1 / its prior variance) on its diagonal, so that
  // a set-up no chosen block uses leaves M regular.
  std::vector<int> nuisance{};
  double nuisancePrior = 0;
  // I-optimal: the weight W (parameters x parameters, symmetric, zero on the nuisance columns).
  Eigen::MatrixXd weight{};
  // A budget instead of a count (budget > 0): candidate c costs cost[c], and each group it belongs
  // to (groups[c]: an instrument's mounting, a sphere's placement) costs groupCost[g] once for
  // all its candidates; the greedy start adds the best gain per cost while it fits, the exchange
  // keeps the total within the budget.
  std::vector<double> cost{};
  std::vector<std::vector<int>> groups{};
  std::vector<double> groupCost{};
  double budget = 0;
  bool repeats = true;  // a candidate may be chosen more than once
};

struct Design {
  std::vector<int> chosen;          // candidate indices, ascending
  double criterion = 0;             // log det M (D) or trace M^-1 (A)
  int exchanges = 0;                // swaps made after the greedy start
  Eigen::MatrixXd information;      // M, the nuisance prior included
  double cost = 0;                  // with a budget: the chosen candidates' total cost
};

// Throws InvalidInput for blocks of different widths, a count (or budget) too small for M to be
// regular, or candidates that leave M singular whatever is chosen (their rank too low).
Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& options);

// The criterion of a given information matrix (log det, trace of the inverse or of W times it;
// -inf / +inf for a singular one: the worst value of each), of the columns not in `nuisance`.
double designCriterion(const Eigen::MatrixXd& information, DesignCriterion criterion, const std::vector<int>& nuisance = {},
                       const Eigen::MatrixXd& weight = {});

}  // namespace mtacc
