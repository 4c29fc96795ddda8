#pragma once
// Which parameters a test plan can determine: the SVD of the plan's Jacobian with columns
// scaled to unit norm; rank, condition number, the parameters without effect and the
// groups the plan cannot separate, each with the combinations that remain observable.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/parallel.hpp"

namespace mtacc {

struct ParameterGroup {
  std::vector<std::string> names;
  // Observable combinations: coefficients (same order as names) of sum c_j p_j, scaled so
  // that the largest |c_j| is 1.
  std::vector<std::vector<double>> observable;
};

struct ObservabilityReport {
  std::vector<std::string> names;
  Eigen::VectorXd singularValues;  // of the column-normalised Jacobian, descending
  // Row i: the right singular vector of singularValues[i] over the parameters (numpy's Vh), in
  // the column-normalised parameters; a parameter without effect has 0 in every row.
  Eigen::MatrixXd singularVectors;
  int rank = 0;
  double condition = 0;             // largest / smallest non-zero singular value
  std::vector<std::string> noEffect;
  std::vector<ParameterGroup> groups;

  bool identifiable() const { return noEffect.empty() && groups.empty(); }
  // One line per finding, e.g. "A0B and A0C act alike: only A0B + 1.000 A0C is observable";
  // `scope` names what the Jacobian covers ("X0C has no effect on this plan").
  std::vector<std::string> findings(const std::string& scope = "this plan") const;
};

// The default relative tolerance of analyseObservability.
constexpr double kRankTolerance = 1e-8;

// `jacobian`: readings x parameters (any units; columns are normalised). A singular value
// below relativeTolerance * the largest counts as zero; a column whose norm is below
// relativeTolerance * the largest column norm (after multiplying by `typical`, the
// parameters' typical sizes) has no effect. Pass the Jacobian with std::move when it is no
// longer needed: it is then factored in place instead of copied.
ObservabilityReport analyseObservability(Eigen::MatrixXd jacobian, const std::vector<std::string>& names,
                                         const Eigen::VectorXd& typical, double relativeTolerance = kRankTolerance,
                                         int threads = kAllCores);

// Which columns to determine when a Jacobian cannot determine them all: a set of full rank
// chosen by column-pivoted QR on the columns scaled by `typical`, after removing the span of the
// columns from `firstAlwaysKept` on (set-up unknowns, estimated in every case). The estimate of
// kept column k then stands for p_k + sum_d standsFor(k, d) p_d over the dropped columns d (held
// at zero), in the columns' own units; a coefficient below 1e-6 in the scaled columns is 0.
struct IdentifiableColumns {
  std::vector<Eigen::Index> kept, dropped;  // among the columns before firstAlwaysKept, ascending
  Eigen::MatrixXd standsFor;                // kept x dropped
};
IdentifiableColumns proposeIdentifiableColumns(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& typical,
                                               Eigen::Index firstAlwaysKept, double relativeTolerance = kRankTolerance);

}  // namespace mtacc
