// Optimal experimental design: the exchange algorithm against the classical optimal designs of
// polynomial regression on [-1, 1] (Atkinson, Donev and Tobias, "Optimum Experimental Designs, with
// SAS", 2007, §11: D-optimal designs put equal weight on the support points -1, 1 for a line and
// -1, 0, 1 for a quadratic; the A-optimal quadratic weights -1, 0, 1 by 1/4, 1/2, 1/4) and
// against a search of every design on small random problems.
#include <gtest/gtest.h>

#include <functional>
#include <random>

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
  EXPECT_EQ(points(designExperiment(line, {DesignCriterion::D, 2})), (std::vector<double>{-1, 1}));
  EXPECT_EQ(points(designExperiment(line, {DesignCriterion::D, 4})), (std::vector<double>{-1, -1, 1, 1}));
  EXPECT_EQ(points(designExperiment(line, {DesignCriterion::A, 2})), (std::vector<double>{-1, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {DesignCriterion::D, 3})), (std::vector<double>{-1, 0, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {DesignCriterion::D, 6})), (std::vector<double>{-1, -1, 0, 0, 1, 1}));
  EXPECT_EQ(points(designExperiment(quadratic, {DesignCriterion::A, 4})), (std::vector<double>{-1, 0, 0, 1}));
  // The D-optimal line's log det: M = [[2, 0], [0, 2]] for {-1, 1}.
  EXPECT_NEAR(designExperiment(line, {DesignCriterion::D, 2}).criterion, std::log(4.0), 1e-12);
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
      const auto d = designExperiment(c, {criterion, 4});
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
  EXPECT_THROW(designExperiment(line, {DesignCriterion::D, 1}), InvalidInput);  // one reading, two parameters
  std::vector<Eigen::MatrixXd> flat(5, Eigen::MatrixXd::Ones(1, 2));            // every candidate the same row
  EXPECT_THROW(designExperiment(flat, {DesignCriterion::D, 3}), InvalidInput);
  EXPECT_THROW(designExperiment({Eigen::MatrixXd::Ones(1, 2), Eigen::MatrixXd::Ones(1, 3)}, {DesignCriterion::D, 2}), InvalidInput);
}

}  // namespace
}  // namespace mtacc
