#pragma once
// The identification of component errors from a hole- or ball-plate campaign (seed 003 §7.7;
// extraction §7): several plate placements, each with its in-plane nuisance translation and
// rotation, solved to first order about the error-free machine. Lengths in mm.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/identification/observability.hpp"
#include "mtacc/measurement/plates.hpp"

namespace mtacc {

// Identification from a plate campaign (§7.7): the chosen machine parameters (to first order
// about the error-free machine, so the problem is linear) and, per placement, an in-plane
// translation and rotation. Parameters the campaign cannot determine are named by the
// observability report and left at zero (the minimum-norm solution in scaled units).
struct PlateCampaign {
  Plate plate;
  std::vector<PlatePlacement> placements;
  std::vector<PlatePoses> poses;             // per placement
  std::vector<Eigen::MatrixX2d> deviations;  // per placement, measured (u, v) per feature, mm
  // Per placement, the standard deviation of a u and a v reading (the probe's), mm: the
  // readings are weighted by them. Empty: equal weights, the scale from the residual.
  std::vector<Eigen::Vector2d> noise;
};
struct PlateIdentification {
  std::vector<std::string> names;  // the machine parameters, then "<placement>.tu", ".tv", ".rot"
  Eigen::VectorXd values, uncertainty;
  Eigen::MatrixXd covariance;
  std::vector<bool> determined;    // false: in a group the campaign cannot separate, or without effect
  double sigma = 0;                // residual standard deviation (mm), or with noise given the ratio to it (should be ~1)
  int readings = 0, degreesOfFreedom = 0;
  ObservabilityReport observability;
};
// The error model a plate identification solves for: `known`'s component functions of the
// linear axes X, Y, Z as they are, and every empty one of them a C1 piecewise quadratic with
// pieces of about `pieceLength` mm over the travel (the functions to find).
ErrorModel plateShape(const Machine& machine, const ErrorModel& known, double pieceLength = 100.0);

// The parameters a plate campaign estimates for the linear axes X, Y, Z (each may be absent):
// the piecewise terms of their component functions in `shape` (continuous ones: the value jumps
// and, for quadratics, the slope jumps at interior breaks stay as given), under the usual gauge
// of a measurement of differences: no constant term of any function (plates see no absolute
// position or orientation); no linear term of a straightness (its line is a squareness); the
// squareness as C0Y (Y about z), B0Z and A0Z (Z about y and x), X's direction and Y's plane
// being the reference (ISO 230-1).
std::vector<Parameter> plateParameters(const Machine& machine, const ErrorModel& shape);

// The standard deviation of a u and a v reading for each placement with the probe seed 003 used
// in its plane (§7.2, half the printed 2S): XY probe 2 (1.1, 0.8 um), XZ probe 1 (0.63, 0.84 um),
// YZ probe 5 (1.4, 7.5 um), by the plate's axes in the workpiece frame.
std::vector<Eigen::Vector2d> seed003ProbeNoise(const std::vector<PlatePlacement>& placements);

// A whole campaign measured on the machine `actual`: the poses of every placement, its
// deviations (simulatePlate) with Gaussian noise of the placement's (sigma_u, sigma_v), and
// that noise as the campaign's weights.
PlateCampaign simulatePlateCampaign(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate,
                                    const std::vector<PlatePlacement>& placements, const std::vector<Eigen::Vector2d>& noise,
                                    std::uint64_t seed);

// The design matrix (readings x parameters, then 3 nuisance columns per placement) of the campaign.
Eigen::MatrixXd plateDesignMatrix(const KinematicModel& withParameters, const PlateCampaign& campaign, int threads = kAllCores);
PlateIdentification identifyFromPlates(const std::shared_ptr<const Machine>& machine, const ErrorModel& shape,
                                       const std::vector<Parameter>& parameters, const PlateCampaign& campaign,
                                       int threads = kAllCores);

}  // namespace mtacc
