#pragma once
// Dynamics of a rigid-body structure model at given axis positions (seed 000 part II, §1.6-
// 1.10 of the reference): assembly of M, K and viscous D (6 DOF per body: translation of the
// centre of gravity and rotation vector, global axes), undamped and damped modes, the 3x3
// FRF of the TCP relative to the workpiece (modal superposition and direct solve), static
// compliance, and the quasi-static response to the acceleration of each axis. SI inside.
#include <complex>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/parallel.hpp"
#include "mtacc/core/statistics.hpp"
#include "mtacc/dynamics/structure.hpp"

namespace mtacc {

constexpr double kStandardGravity = 9.80665;  // m/s^2 (seed 000 L5935)

struct StructureMatrices {
  Eigen::MatrixXd mass, stiffness, damping;   // 6N x 6N
  Eigen::Matrix<double, 3, Eigen::Dynamic> selection;  // relative TCP - workpiece displacement = S q
  Eigen::MatrixXd inertialLoads;  // 6N x axes: -M E_j, the load of a unit acceleration of axis j
};

// "Y = 500 mm beyond travel [-400, 400] mm" for the first axis position outside its travel
// (or not finite); empty when all are within.
std::string travelViolation(const StructureModel& model, const std::vector<double>& positions);

// Axis positions in m, one per StructureModel::axes (empty = all at 0). Throws InputError for
// a wrong count or a position beyond travel.
StructureMatrices assembleStructure(const StructureModel& model, const std::vector<double>& positions = {});

struct Modes {
  Eigen::VectorXd frequencies;  // Hz, ascending
  Eigen::MatrixXd shapes;       // columns, mass-normalised (phi^T M phi = 1)
};
// Throws InputError when K is singular (a body not held in some direction), naming the body
// and the direction of the free motion.
Modes undampedModes(const StructureModel& model, const StructureMatrices& m);
// The same for several sets of matrices (of the model at several positions), solved together:
// faster than one at a time (symmetricEigen).
std::vector<Modes> undampedModes(const StructureModel& model, std::span<const StructureMatrices> matrices);

// phi_r^T D phi_r per mode (1/s): the modal equations q'' + c_r q' + w_r^2 q = phi_r^T f,
// exact for proportional damping.
Eigen::VectorXd modalDampingCoefficients(const StructureMatrices& m, const Modes& modes);
// How far the damping is from proportional: the largest off-diagonal term of phi^T D phi over
// the geometric mean of its two diagonal terms. 0 when the modal sum is exact.
double modalDampingCoupling(const StructureMatrices& m, const Modes& modes);

struct DampedMode {
  double frequency;     // Hz, |lambda| / 2 pi
  double dampingRatio;  // -Re(lambda) / |lambda|
};
std::vector<DampedMode> dampedModes(const StructureMatrices& m);

using Frf = std::vector<Eigen::Matrix3cd>;  // per frequency, m/N: H(i, j) = displacement i / force j
// (K - w^2 M + j w D)^-1 between the TCP-workpiece force pair and the relative displacement.
Frf frfDirect(const StructureMatrices& m, const std::vector<double>& frequencies);
// Sum over all modes with modal damping phi_r^T D phi_r (exact for proportional damping).
Frf frfModal(const StructureMatrices& m, const Modes& modes, const std::vector<double>& frequencies);
Eigen::Matrix3d staticCompliance(const StructureMatrices& m);
// At each set of axis positions: the largest |H_ij| over the frequencies (modal
// superposition, all modes), m/N; threads as in core/parallel.hpp.
std::vector<Eigen::Matrix3d> frfPeaks(const StructureModel& model, const std::vector<std::vector<double>>& positions,
                                      const std::vector<double>& frequencies, int threads = kAllCores);
// Quasi-static relative displacement per acceleration of each axis: 3 x axes, m per (m/s^2);
// multiply by kStandardGravity * 1e6 for um/g_n (the form of seed 000 Table 7.1).
Eigen::Matrix<double, 3, Eigen::Dynamic> accelerationResponse(const StructureMatrices& m);

// A scalar evaluated at a set of axis positions, e.g. |H_x / x''| in um/g_n: one value per
// set of matrices given (a mode's frequency solves their eigenproblems together).
struct DynamicsQuantity {
  std::string name;  // "Hx/X" (um/g_n), "Cxy" (static compliance, um/N), "f1" (Hz)
  std::string unit;
  std::function<std::vector<double>(const StructureModel&, std::span<const StructureMatrices>)> evaluate;
};
// Parses "H<x|y|z>/<axis>", "C<x|y|z><x|y|z>" or "f<n>"; throws InputError otherwise.
DynamicsQuantity dynamicsQuantity(const StructureModel& model, const std::string& name);

// The quantity over a grid of two axes (the others at `fixed`, m), e.g. 20 x 20 over Y-Z
// (seed 000 L6213-6227), with its distribution statistics.
struct DynamicsMap {
  std::string axisA, axisB;
  std::vector<double> a, b;   // grid positions, m
  Eigen::MatrixXd values;     // a x b
  BoxStatistics statistics;
};
struct MapGrid {
  std::string axisA = "Y", axisB = "Z";
  int countA = 20, countB = 20;
  std::vector<double> fixed;  // all axes, m (those of the grid are overwritten); empty: all 0
};
DynamicsMap dynamicsMap(const StructureModel& model, const MapGrid& grid, const DynamicsQuantity& quantity,
                        int threads = kAllCores);

}  // namespace mtacc
