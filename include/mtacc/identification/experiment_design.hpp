#pragma once
// Optimal experimental design over a candidate set: which candidates (a pose of an instrument, each
// giving a block of readings) to measure so that the parameters are best determined. The
// candidates' blocks are rows of the readings' Jacobian, each divided by its reading's noise, so that
// the information matrix of a design is M = sum of J_b^T J_b over its blocks (the inverse of the
// estimates' covariance). D-optimal: the largest log det M (the smallest joint uncertainty);
// A-optimal: the smallest trace M^-1 (the sum of the variances). A greedy start, then Fedorov's
// exchange: the best swap of a chosen block for a candidate, through the determinant and Woodbury
// identities of the low-rank change (no refactorisation per trial), until no swap improves it.
#include <vector>

#include <Eigen/Core>

namespace mtacc {

enum class DesignCriterion { D, A };
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
};

struct Design {
  std::vector<int> chosen;          // candidate indices, ascending
  double criterion = 0;             // log det M (D) or trace M^-1 (A)
  int exchanges = 0;                // swaps made after the greedy start
  Eigen::MatrixXd information;      // M, the nuisance prior included
};

// Throws InvalidInput for blocks of different widths, a count below the parameters' number (M
// singular), or candidates that leave M singular whatever is chosen (their rank too low).
Design designExperiment(const std::vector<Eigen::MatrixXd>& candidates, const DesignOptions& options);

// The criterion of a given information matrix (log det, or trace of the inverse; -inf / +inf for
// a singular one: the worst value of each), of the columns not in `nuisance`.
double designCriterion(const Eigen::MatrixXd& information, DesignCriterion criterion, const std::vector<int>& nuisance = {});

}  // namespace mtacc
