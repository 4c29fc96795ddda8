#pragma once
// Hole plates and ball plates (seed 003 ch. 4.3, 5.3, App. C; extraction §7): a calibrated
// grid of features probed on the machine in any plane and position. Simulation of a plate
// measurement (D_h = -(E(q_h) - E(q_ref)), axis positions from the generic inverse kinematics),
// processing of measured plates (temperatures, misalignment), the k = 2 budget of the
// residual model - measurement (§7.5). The identification from several plate positions is in
// identification/plate_identification.hpp.
// Lengths in mm; in-plane deviations along the plate's u (rows) and v (columns) axes.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/measurement/artefact.hpp"

namespace mtacc {

struct Plate {
  std::string name;
  int rows = 9, columns = 9;
  double pitch = 50.0;
  // Calibrated feature centres in the plate frame (u along a row, v along a column), one per
  // feature, row-major from the reference feature (0, 0); empty: the nominal grid.
  std::vector<Eigen::Vector2d> calibrated;
  double calibrationUncertainty = 0.35e-3;  // standard uncertainty of a centre (PTB: 2S = 0.7 um)

  Eigen::Vector2d centre(int row, int column) const;
};

// The features a placement probes: all, or the outer ring only (seed 003 L3013-3015).
enum class PlateFeatures { All, Outer };

struct PlatePlacement {
  std::string name;
  Vec3 origin = Vec3::Zero();    // reference feature (0, 0), workpiece frame
  Vec3 u = Vec3::UnitX();        // plate axes in the workpiece frame (orthonormal)
  Vec3 v = Vec3::UnitY();
  Vec3 stylus = Vec3::Zero();    // probe tip relative to the TCP, tool frame
  std::vector<double> fixedAxes;  // positions (mm, rad) of every axis for the IK hint; the rotaries stay there
  PlateFeatures features = PlateFeatures::All;
};

// The probed features of one placement: their (row, column), the axis positions reaching each
// (rotaries at the placement's fixed values), first the reference feature.
struct PlatePoses {
  std::vector<std::pair<int, int>> features;
  JointMatrix q;
};
// Throws UnreachablePose naming the feature that cannot be reached within travel.
PlatePoses platePoses(const KinematicModel& nominal, const Plate& plate, const PlatePlacement& placement);

// The plate as an artefact: the features "R<row>C<column>" at their calibrated (u, v, 0) relative
// to the first of `features` (the reference feature (0, 0)), each with the plate's calibration
// uncertainty; and its placement, its origin at the reference feature, probed in the plate plane.
Artefact plateArtefact(const Plate& plate, const std::vector<std::pair<int, int>>& features);
ArtefactPlacement artefactPlacement(const Plate& plate, const PlatePlacement& placement);

// A campaign over the working volume of the linear axes (rotaries at the reference pose), as
// seed 003 §7.7 describes it: plates in the three coordinate planes of the workpiece frame, in
// each plane at the two ends of both in-plane ranges (2 x 2 positions) and on two levels along the
// normal (a quarter and three quarters of its range), the second level probed with a stylus
// `stylus` mm off the TCP along the normal (a second stylus, for the rotations): 24 placements,
// named XY1..XY8, XZ9..XZ16, YZ17..YZ24. Throws InvalidInput when the plate does not fit.
std::vector<PlatePlacement> cubePlacements(const KinematicModel& nominal, const Plate& plate, double stylus = 60.0);

// Deviations (u, v) of each probed feature relative to the reference feature, as the machine
// with `actual`'s errors measures them (D_h = -(E(q_h) - E(q_ref)), the sign of docs/conventions.md), mm; one row per
// feature, the reference first (zero).
Eigen::MatrixX2d simulatePlate(const KinematicModel& actual, const KinematicModel& nominal, const Plate& plate,
                               const PlatePlacement& placement, const PlatePoses& poses);

// The temperatures of a plate or artefact measurement (§7.3): the machine scales' reading and
// the artefact's size are referred to the reference temperature.
struct PlateTemperatures {
  double scale = 20.0, plate = 20.0, reference = 20.0;  // deg C
  double scaleExpansion = 0.0, plateExpansion = 0.0;     // 1/K
};
// The features' calibrated positions relative to the first (the reference feature), mm.
std::vector<Eigen::Vector2d> featurePositions(const Plate& plate, const std::vector<std::pair<int, int>>& features);

// The k = 2 bound of a residual model - measurement (§7.5): the simulation's own 2S once, and
// for each of the two features of a difference the plate calibration, the probe's
// repeatability in both plate axes, the scale- and plate-expansion corrections.
struct ResidualBudget {
  double simulation = 0, plate = 0, probeU = 0, probeV = 0, scaleCorrection = 0, plateCorrection = 0;  // each 2S
};
double residualBound(const ResidualBudget& budget);

}  // namespace mtacc
