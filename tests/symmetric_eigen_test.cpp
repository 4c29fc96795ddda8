#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>

#include "mtacc/core/symmetric_eigen.hpp"

namespace mtacc {
namespace {

std::vector<SymmetricEigen> solved(const std::vector<Eigen::MatrixXd>& matrices) {
  std::vector<SymmetricEigen> out(matrices.size());
  symmetricEigen(matrices, out);
  return out;
}

Eigen::MatrixXd randomSymmetric(int n, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(n, n);
  return r + r.transpose();
}

// A rotated diagonal: the eigenvalues are known exactly.
Eigen::MatrixXd withEigenvalues(const Eigen::VectorXd& values, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(values.size(), values.size())).householderQ();
  return q * values.asDiagonal() * q.transpose();
}

// Against Eigen's SelfAdjointEigenSolver (values), and A V = V diag(values), V^T V = I,
// all to a few units of rounding of |A|.
void expectDecomposition(const Eigen::MatrixXd& a, const SymmetricEigen& s) {
  ASSERT_TRUE(s.converged);
  const Eigen::Index n = a.rows();
  const double norm = std::max(a.norm(), 1e-300), tolerance = 50 * n * std::numeric_limits<double>::epsilon();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> reference(a, Eigen::EigenvaluesOnly);
  EXPECT_LE((s.values - reference.eigenvalues()).cwiseAbs().maxCoeff(), tolerance * norm);
  EXPECT_LE((a * s.vectors - s.vectors * s.values.asDiagonal()).norm(), tolerance * norm);
  EXPECT_LE((s.vectors.transpose() * s.vectors - Eigen::MatrixXd::Identity(n, n)).norm(), tolerance);
  for (Eigen::Index i = 1; i < n; ++i) EXPECT_LE(s.values[i - 1], s.values[i]);
}

TEST(SymmetricEigen, AgreesWithEigensSolverOnABatchOfMixedSizes) {
  // Nine matrices: two full groups of four sweeps in flight and one alone.
  std::vector<Eigen::MatrixXd> matrices;
  for (int n : {60, 1, 2, 3, 7, 60, 13, 33, 5}) matrices.push_back(randomSymmetric(n, static_cast<unsigned>(n + matrices.size())));
  const auto out = solved(matrices);
  for (size_t i = 0; i < matrices.size(); ++i) {
    SCOPED_TRACE(i);
    expectDecomposition(matrices[i], out[i]);
  }
}

TEST(SymmetricEigen, GradedSpectrumOfAStructure) {
  // Eigenvalues from 1e-7 to 1, as the structure model's (w^2 from 47 Hz to 150 kHz): the
  // small ones are resolved to eps |A| as by any backward-stable solver.
  Eigen::VectorXd values(40);
  for (int i = 0; i < 40; ++i) values[i] = std::pow(10.0, -7.0 + 7.0 * i / 39);
  const Eigen::MatrixXd a = withEigenvalues(values, 3);
  const auto out = solved({a});
  expectDecomposition(a, out[0]);
  EXPECT_LE((out[0].values - values).cwiseAbs().maxCoeff(), 100 * std::numeric_limits<double>::epsilon());
}

TEST(SymmetricEigen, SecondDifferenceMatrixHasItsClosedFormEigenvalues) {
  // tridiag(-1, 2, -1) of size n: 2 - 2 cos(k pi / (n + 1)), k = 1..n.
  const int n = 50;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) a(i, i) = 2;
  for (int i = 0; i + 1 < n; ++i) a(i + 1, i) = a(i, i + 1) = -1;
  const auto out = solved({a});
  ASSERT_TRUE(out[0].converged);
  for (int k = 1; k <= n; ++k) EXPECT_NEAR(out[0].values[k - 1], 2 - 2 * std::cos(k * std::numbers::pi / (n + 1)), 1e-14);
}

TEST(SymmetricEigen, RepeatedEigenvaluesKeepOrthonormalVectors) {
  Eigen::VectorXd values(9);
  values << 1, 1, 1, 2, 2, 3, 3, 3, 3;
  const Eigen::MatrixXd a = withEigenvalues(values, 7);
  const auto out = solved({a, Eigen::MatrixXd::Identity(6, 6) * 4.0});
  expectDecomposition(a, out[0]);
  EXPECT_LE((out[0].values - values).cwiseAbs().maxCoeff(), 1e-14);
  expectDecomposition(Eigen::MatrixXd::Identity(6, 6) * 4.0, out[1]);
}

TEST(SymmetricEigen, DiagonalAndDecoupledMatricesAreSortedAndExact) {
  Eigen::MatrixXd diagonal = Eigen::Vector4d(3, -1, 2, 0).asDiagonal();
  const auto out = solved({diagonal, Eigen::MatrixXd::Zero(3, 3), Eigen::MatrixXd(0, 0)});
  ASSERT_TRUE(out[0].converged);
  EXPECT_EQ(out[0].values, Eigen::Vector4d(-1, 0, 2, 3));
  Eigen::MatrixXd permutation = Eigen::MatrixXd::Zero(4, 4);
  permutation(1, 0) = permutation(3, 1) = permutation(2, 2) = permutation(0, 3) = 1;
  EXPECT_EQ(out[0].vectors, permutation);
  ASSERT_TRUE(out[1].converged);
  EXPECT_EQ(out[1].values, Eigen::Vector3d::Zero());
  EXPECT_EQ(out[1].vectors, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(out[2].converged);
  EXPECT_EQ(out[2].values.size(), 0);

  // Two blocks that do not couple: the tridiagonal splits.
  Eigen::MatrixXd blocks = Eigen::MatrixXd::Zero(10, 10);
  blocks.topLeftCorner(4, 4) = randomSymmetric(4, 11);
  blocks.bottomRightCorner(6, 6) = randomSymmetric(6, 12);
  expectDecomposition(blocks, solved({blocks})[0]);
}

TEST(SymmetricEigen, ReadsOnlyTheLowerTriangleAndRefusesNonFiniteEntries) {
  Eigen::MatrixXd a = randomSymmetric(8, 5);
  Eigen::MatrixXd upperGarbage = a;
  upperGarbage(1, 6) = std::numeric_limits<double>::quiet_NaN();
  upperGarbage(0, 7) = 1e300;
  Eigen::MatrixXd lowerNan = a;
  lowerNan(6, 1) = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd lowerInf = a;
  lowerInf(7, 7) = std::numeric_limits<double>::infinity();
  const auto out = solved({upperGarbage, lowerNan, lowerInf, a});
  expectDecomposition(a, out[0]);
  EXPECT_FALSE(out[1].converged);
  EXPECT_FALSE(out[2].converged);
  expectDecomposition(a, out[3]);  // a refused neighbour does not disturb the others
}

}  // namespace
}  // namespace mtacc
