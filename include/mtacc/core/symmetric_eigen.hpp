#pragma once
// All eigenvalues and eigenvectors of several real symmetric matrices at once: the FRF map
// solves one 60 x 60 problem per axis position, ten thousand of them.
//
// Per matrix, Eigen's Householder tridiagonalisation, then the implicit symmetric QR iteration
// with Wilkinson's shift (Golub and Van Loan, Matrix Computations, 4th ed., Algorithm 8.3.3).
// What Eigen's SelfAdjointEigenSolver does, except that the QR sweeps of the matrices run
// interleaved, one rotation of each in turn: each rotation of a sweep waits for the square
// root and the division of the one before, and on its own a 60 x 60 problem spends most of its
// sweeps waiting so (LAPACK's dsyevd and dsyevr, through OpenBLAS, are slower still at this
// size). The sweeps of the other matrices fill that wait.
#include <cstddef>
#include <span>

#include <Eigen/Core>

namespace mtacc {

// How many matrices' sweeps run interleaved: four cover a rotation's latency, more gain nothing
// (measured at 60 x 60). A caller with many problems hands them over at least this many at a time.
constexpr size_t kInterleavedEigenproblems = 4;

struct SymmetricEigen {
  Eigen::VectorXd values;   // ascending
  Eigen::MatrixXd vectors;  // orthonormal; column k belongs to values[k]
  // False when the matrix has an entry that is not finite, or when the iteration did not
  // converge in 30 sweeps per row; values and vectors are then not meaningful.
  bool converged = false;
};

// Reads the lower triangle of each matrix; the matrices may differ in size. out.size() must
// equal matrices.size(); each entry's storage is reused when it has the size already.
void symmetricEigen(std::span<const Eigen::MatrixXd> matrices, std::span<SymmetricEigen> out);

}  // namespace mtacc
