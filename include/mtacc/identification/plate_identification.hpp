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

// Identification from a campaign of artefact placements (§7.7 for plates; step gauges, ball bars
// and 3-D artefacts alike): the chosen machine parameters (to first order about the error-free
// machine, so the problem is linear) and, per placement, a translation along each probed
// direction and the rotations that move its features along them. Parameters the campaign cannot
// determine are named by the observability report and left at zero (the minimum-norm solution
// in scaled units).
struct CampaignPlacement {
  ArtefactPlacement placement;  // its frame gives the probed directions u (, v (, w))
  int dimension = 2;            // of the artefact: which rotations move its features
  Eigen::MatrixX3d positions;   // the features' places relative to the first, workpiece frame, mm
  JointMatrix poses;            // per feature
  Eigen::MatrixXd deviations;   // per feature and probed direction, mm
  // The standard deviation of a reading per probed direction (the probe's), mm: the readings
  // are weighted by them. Empty in every placement: equal weights, the scale from the residual.
  Eigen::VectorXd noise;
};
using ArtefactCampaign = std::vector<CampaignPlacement>;
// The nuisance rotation axes of a placement (workpiece frame): none for a reading along one
// direction, the normal for a plane, all three in space (two for features on one line).
std::vector<Vec3> nuisanceRotations(const CampaignPlacement& placement);
// A plate placement of a campaign: features, poses and (u, v) deviations as simulatePlate gives them.
CampaignPlacement plateCampaignPlacement(const Plate& plate, const PlatePlacement& placement, const PlatePoses& poses,
                                         const Eigen::MatrixX2d& deviations, const Eigen::Vector2d& noise);
struct PlateIdentification {
  std::vector<std::string> names;  // the machine parameters, then "<placement>.tu" (.tv, .tw) and ".ru" (.rv, .rw)
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
ArtefactCampaign simulatePlateCampaign(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate,
                                    const std::vector<PlatePlacement>& placements, const std::vector<Eigen::Vector2d>& noise,
                                    std::uint64_t seed);

// A nuisance parameter's name "<placement>.r?" is a rotation (rad), ".t?" a translation (mm).
bool isNuisanceRotation(const std::string& name);

// The design matrix (readings x parameters, then the nuisance columns of each placement) of the campaign.
Eigen::MatrixXd artefactDesignMatrix(const KinematicModel& withParameters, const ArtefactCampaign& campaign, int threads = kAllCores);
PlateIdentification identifyFromArtefacts(const std::shared_ptr<const Machine>& machine, const ErrorModel& shape,
                                       const std::vector<Parameter>& parameters, const ArtefactCampaign& campaign,
                                       int threads = kAllCores);

}  // namespace mtacc
