#pragma once
// The dense decompositions of Eigen::MatrixXd that several files use, instantiated once, in
// src/core/decompositions.cpp: each costs 10-60 s of compile time (more under the sanitizers)
// in every file that instantiates it itself. Include this instead of <Eigen/QR> and <Eigen/SVD>.
#include <Eigen/QR>
#include <Eigen/SVD>

extern template class Eigen::BDCSVD<Eigen::MatrixXd>;
extern template class Eigen::JacobiSVD<Eigen::MatrixXd>;
extern template class Eigen::ColPivHouseholderQR<Eigen::MatrixXd>;
