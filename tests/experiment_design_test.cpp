// Optimal experimental design: the exchange algorithm against the classical optimal designs of
// polynomial regression on [-1, 1] (Atkinson, Donev and Tobias, "Optimum Experimental Designs, with
// SAS", 2007, §11: D-optimal designs put equal weight on the support points -1, 1 for a line and
// -1, 0, 1 for a quadratic; the A-optimal quadratic weights -1, 0, 1 by 1/4, 1/2, 1/4) and
// against a search of every design on small random problems.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>

#include <Eigen/LU>

#include "mtacc/core/input_error.hpp"
#include "mtacc/identification/experiment_design.hpp"

namespace mtacc {
namespace {

// One reading per candidate x on a grid of [-1, 1] in steps of 0.1: the row (1, x, ..., x^degree).
std::vector<Eigen::MatrixXd> polynomialCandidates(int degree) {
  std::vector<Eigen::MatrixXd> out;
  for (int i = -10; i <= 10; ++i) {
    Eigen::MatrixXd row(1, degree + 1);
    for (int k = 0; k <= degree; ++k) row(0, k) = std::pow(i / 10.0, k);
    out.push_back(row);
  }
  return out;
}

std::vector<double> points(const Design& d) {
  std::vector<double> x;
  for (int i : d.chosen) x.push_back((i - 10) / 10.0);
  return x;
}

TEST(ExperimentDesign, ClassicalOptimaOfPolynomialRegression) {
  const auto line = polynomialCandidates(1), quadratic = polynomialCandidates(2);
  EXPECT_EQ(points(designExperiment(line, {.criterion = DesignCriterion::D, .count = 2})), (std::vector<double>{-1, 1}));
  EXPECT_EQ(points(designExperiment(line, {.criterion = DesignCriterion::D, .count = 4})), (std::vector<double>{-1, -1, 1, 1}));
  EXPECT_EQ(points(designExperiment(line, {.criterion = DesignCriterion::A, .count = 2})), (std::vector<double>{-1, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {.criterion = DesignCriterion::D, .count = 3})), (std::vector<double>{-1, 0, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {.criterion = DesignCriterion::D, .count = 6})), (std::vector<double>{-1, -1, 0, 0, 1, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {.criterion = DesignCriterion::A, .count = 4})), (std::vector<double>{-1, 0, 0, 1}));
  // The D-optimal line's log det: M = [[2, 0], [0, 2]] for {-1, 1}.
  EXPECT_NEAR(designExperiment(line, {.criterion = DesignCriterion::D, .count = 2}).criterion, std::log(4.0), 1e-12);
}

// Every multiset of `count` candidates, the best criterion among them.
double bestByEnumeration(const std::vector<Eigen::MatrixXd>& c, int count, DesignCriterion criterion) {
  double best = criterion == DesignCriterion::D ? -INFINITY : INFINITY;
  std::vector<int> chosen;
  const std::function<void(int)> walk = [&](int from) {
    if (static_cast<int>(chosen.size()) == count) {
      Eigen::MatrixXd m = Eigen::MatrixXd::Zero(c[0].cols(), c[0].cols());
      for (int i : chosen) m += c[static_cast<size_t>(i)].transpose() * c[static_cast<size_t>(i)];
      const double v = designCriterion(m, criterion);
      best = criterion == DesignCriterion::D ? std::max(best, v) : std::min(best, v);
      return;
    }
    for (int i = from; i < static_cast<int>(c.size()); ++i) {
      chosen.push_back(i);
      walk(i);
      chosen.pop_back();
    }
  };
  walk(0);
  return best;
}

TEST(ExperimentDesign, ReachesTheBestDesignOfSmallRandomProblems) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  int optimal = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::MatrixXd> c(9);
    for (auto& block : c) block = Eigen::MatrixXd::NullaryExpr(2, 4, [&] { return normal(rng); });  // two readings, four parameters
    for (const auto criterion : {DesignCriterion::D, DesignCriterion::A}) {
      const double best = bestByEnumeration(c, 4, criterion);
      const auto d = designExperiment(c, {.criterion = criterion, .count = 4});
      EXPECT_NEAR(d.criterion, designCriterion(d.information, criterion), 1e-9);
      // An exchange finds a local optimum: its efficiency against the global one.
      const double efficiency = criterion == DesignCriterion::D ? std::exp((d.criterion - best) / 4) : best / d.criterion;
      EXPECT_GT(efficiency, 0.97) << "trial " << trial << " " << toString(criterion);
      optimal += efficiency > 1 - 1e-9;
    }
  }
  EXPECT_GE(optimal, 36);  // of 40: the exchange usually reaches the optimum itself
}

TEST(ExperimentDesign, RefusesWhatCannotDetermineTheParameters) {
  const auto line = polynomialCandidates(1);
  EXPECT_THROW(designExperiment(line, {.criterion = DesignCriterion::D, .count = 1}), InvalidInput);  // one reading, two parameters
  std::vector<Eigen::MatrixXd> flat(5, Eigen::MatrixXd::Ones(1, 2));            // every candidate the same row
  EXPECT_THROW(designExperiment(flat, {.criterion = DesignCriterion::D, .count = 3}), InvalidInput);
  EXPECT_THROW(designExperiment({Eigen::MatrixXd::Ones(1, 2), Eigen::MatrixXd::Ones(1, 3)}, {.criterion = DesignCriterion::D, .count = 2}), InvalidInput);
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

TEST(ExperimentDesign, NuisanceCriteriaAreThoseOfTheSchurComplement) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  const Eigen::MatrixXd j = Eigen::MatrixXd::NullaryExpr(12, 5, [&] { return normal(rng); });
  const Eigen::MatrixXd m = j.transpose() * j;
  const std::vector<int> nuisance{1, 4};
  // The others' information once the nuisance is estimated: M_ii - M_in M_nn^-1 M_ni.
  const std::vector<int> interest{0, 2, 3};
  Eigen::MatrixXd mii(3, 3), min(3, 2), mnn(2, 2);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) mii(a, b) = m(interest[a], interest[b]);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 2; ++b) min(a, b) = m(interest[a], nuisance[b]);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) mnn(a, b) = m(nuisance[a], nuisance[b]);
  const Eigen::MatrixXd schur = mii - min * mnn.inverse() * min.transpose();
  EXPECT_NEAR(designCriterion(m, DesignCriterion::D, nuisance), std::log(schur.determinant()), 1e-10);
  EXPECT_NEAR(designCriterion(m, DesignCriterion::A, nuisance), schur.inverse().trace(), 1e-12);
}

TEST(ExperimentDesign, ClassicalOptimaForOneCoefficientWithTheOthersAsNuisance) {
  // The leading coefficient of a polynomial of degree d on [-1, 1] is best estimated on the
  // Chebyshev points with weights 1/2d, 1/d, ..., 1/2d (Kiefer and Wolfowitz 1959): for a line's
  // slope -1 and 1, for a quadratic's x^2 coefficient -1, 0, 1 weighted 1/4, 1/2, 1/4.
  const auto line = polynomialCandidates(1), quadratic = polynomialCandidates(2);
  for (const auto criterion : {DesignCriterion::D, DesignCriterion::A}) {
    EXPECT_EQ(points(designExperiment(line, {.criterion = criterion, .count = 4, .nuisance = {0}})), (std::vector<double>{-1, -1, 1, 1}));
    EXPECT_EQ(points(designExperiment(quadratic, {.criterion = criterion, .count = 4, .nuisance = {0, 1}})),
              (std::vector<double>{-1, 0, 0, 1}));
    const auto d = designExperiment(quadratic, {.criterion = criterion, .count = 8, .nuisance = {0, 1}});
    EXPECT_EQ(points(d), (std::vector<double>{-1, -1, 0, 0, 0, 0, 1, 1}));
    EXPECT_NEAR(d.criterion, designCriterion(d.information, criterion, {0, 1}), 1e-12);
  }
}

TEST(ExperimentDesign, ANuisancePriorKeepsAnUnusedSetUpRegular) {
  // Two set-ups, each with its own offset (columns 1 and 2) beside the parameter of interest
  // (column 0); every candidate reads one set-up only. With a prior on the offsets the design may
  // use one set-up alone; without one, a design that leaves a set-up unused is singular.
  std::vector<Eigen::MatrixXd> c;
  for (int setUp = 0; setUp < 2; ++setUp)
    for (int i = -2; i <= 2; ++i) {
      Eigen::MatrixXd row = Eigen::MatrixXd::Zero(1, 3);
      row(0, 0) = i * (setUp == 0 ? 1.0 : 0.5);  // the first set-up sees the parameter twice as well
      row(0, 1 + setUp) = 1.0;
      c.push_back(row);
    }
  const auto d = designExperiment(c, {.criterion = DesignCriterion::D, .count = 4, .nuisance = {1, 2}, .nuisancePrior = 1e-6});
  for (int i : d.chosen) EXPECT_LT(i, 5) << "the weaker set-up was chosen";
  EXPECT_EQ(d.chosen, (std::vector<int>{0, 0, 4, 4}));  // the first set-up's ends, x = -2 and 2, twice each
  // Without the prior the second set-up's offset needs a reading of its own: one, which tells
  // nothing of the parameter once its offset is estimated, beside three of the first set-up.
  const auto noPrior = designExperiment(c, {.criterion = DesignCriterion::D, .count = 4, .nuisance = {1, 2}});
  EXPECT_EQ(std::count_if(noPrior.chosen.begin(), noPrior.chosen.end(), [](int i) { return i >= 5; }), 1);
}

TEST(ExperimentDesign, IOptimalQuadraticIsTheClassicalOne) {
  // The integrated variance over [-1, 1]: W = (1/2) int f f^T dx for f = (1, x, x^2). The I- (V-)
  // optimal design for the quadratic puts weights 1/4, 1/2, 1/4 on -1, 0, 1 (the classical result;
  // over symmetric weights w, 1 - 2w, w, trace(W M(w)^-1) is least at w = 1/4, 32/15).
  Eigen::MatrixXd w(3, 3);
  w << 1, 0, 1.0 / 3, 0, 1.0 / 3, 0, 1.0 / 3, 0, 1.0 / 5;
  const auto quadratic = polynomialCandidates(2);
  const auto d = designExperiment(quadratic, {.criterion = DesignCriterion::I, .count = 8, .weight = w});
  EXPECT_EQ(points(d), (std::vector<double>{-1, -1, 0, 0, 0, 0, 1, 1}));
  // trace(W M^-1) for M = 8 (1/4 f(-1) f(-1)^T + 1/2 f(0) f(0)^T + 1/4 f(1) f(1)^T): 32/15 / 8.
  EXPECT_NEAR(d.criterion, 32.0 / 15.0 / 8.0, 1e-12);
  EXPECT_NEAR(d.criterion, designCriterion(d.information, DesignCriterion::I, {}, w), 1e-14);
}

TEST(ExperimentDesign, ABudgetTradesCostAgainstInformation) {
  // A line on [-1, 1]; the ends cost 2, every other point 1; a budget of 4, no repeats: the two
  // ends give det M = 4, the four points -0.9, -0.8, 0.8, 0.9 det M = 4 (2 0.81 + 2 0.64) = 11.6.
  const auto line = polynomialCandidates(1);
  std::vector<double> cost(line.size(), 1.0);
  cost.front() = cost.back() = 2.0;
  const auto d = designExperiment(line, {.criterion = DesignCriterion::D, .cost = cost, .budget = 4, .repeats = false});
  EXPECT_EQ(points(d), (std::vector<double>{-0.9, -0.8, 0.8, 0.9}));
  EXPECT_NEAR(d.cost, 4.0, 1e-12);
  EXPECT_NEAR(d.criterion, std::log(4 * (2 * 0.81 + 2 * 0.64)), 1e-12);
  // A group's cost counts once: the negative side needs a mounting of 10, beyond the budget, so
  // the design keeps to [0, 1], its ends and their neighbours.
  std::vector<std::vector<int>> groups;
  for (size_t i = 0; i < line.size(); ++i) groups.push_back({i < 10 ? 0 : 1});
  const auto g = designExperiment(line, {.criterion = DesignCriterion::D, .cost = std::vector<double>(line.size(), 1.0), .groups = groups,
                                         .groupCost = {10.0, 0.0}, .budget = 4, .repeats = false});
  EXPECT_EQ(points(g), (std::vector<double>{0, 0.1, 0.9, 1}));
  EXPECT_NEAR(g.cost, 4.0, 1e-12);
  EXPECT_THROW(designExperiment(line, {.criterion = DesignCriterion::D, .cost = cost, .budget = 1.5, .repeats = false}), InvalidInput);
}

}  // namespace
}  // namespace mtacc
