#pragma once
// Calibrated artefacts probed on the machine (seed 003 ch. 4.3 generalised; docs/file-formats.md
// "Artefact measurements"): a step gauge or ball bar (1-D), a ball or hole plate (2-D) or any
// set of features in space (3-D), each feature's position given by its calibration certificate
// in the artefact's own frame (u, v, w), the artefact placed anywhere in the working volume.
// The machine's deviation at each feature, the alignment of the certificate onto the
// measurement (least squares or the three-point alignment of common practice) and the k = 2
// uncertainty of each deviation. Lengths in mm.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

struct ArtefactFeature {
  std::string id;
  Vec3 calibrated = Vec3::Zero();  // certificate position, artefact frame (u, v, w), mm
  double uncertainty = 0.0;        // standard uncertainty of each calibrated coordinate, mm
};

struct Artefact {
  std::string name;
  int dimension = 3;  // 1: features along u (step gauge, ball bar); 2: in the u-v plane (plate); 3: anywhere
  std::vector<ArtefactFeature> features;
};

// The directions in which the probing measures a feature: u, v, w (a ball or sphere probed on
// its surface), u and v (a hole probed on its wall), or u alone (a gauge read along its axis).
enum class ProbedDirections { All, InPlane, Along };
int directionCount(ProbedDirections probed);

struct ArtefactPlacement {
  std::string name;
  Vec3 origin = Vec3::Zero();  // the artefact frame's origin in the workpiece frame
  Vec3 u = Vec3::UnitX(), v = Vec3::UnitY();  // orthonormal, workpiece frame; w = u x v
  Vec3 stylus = Vec3::Zero();                 // probe tip relative to the TCP, tool frame
  std::vector<double> fixedAxes;              // every commanded axis (mm, rad); the rotaries stay there
  ProbedDirections probed = ProbedDirections::All;

  Eigen::Matrix3d frame() const;  // columns u, v, w
  Vec3 place(const Vec3& artefactPoint) const { return origin + frame() * artefactPoint; }
};

// The axis positions reaching each feature's calibrated place (nominal inverse kinematics of
// the tool point, the rotaries at the placement's fixed values); throws UnreachablePose naming
// the feature.
JointMatrix artefactPoses(const KinematicModel& nominal, const Artefact& artefact, const ArtefactPlacement& placement);

// Per feature, where the machine with `actual`'s errors reports the stylus when it touches the
// feature, minus the feature's true place: -(E(q_h)), E the tool point's actual minus nominal
// position (docs/conventions.md), workpiece frame, mm.
Eigen::MatrixX3d artefactProbingErrors(const KinematicModel& actual, const KinematicModel& nominal, const ArtefactPlacement& placement,
                                       const JointMatrix& poses);

enum class AlignmentMethod { LeastSquares, LeastSquaresScaled, ThreePoint };
struct Alignment {
  AlignmentMethod method = AlignmentMethod::LeastSquares;
  // ThreePoint: the features (indices) that set the origin, the first direction and the plane;
  // unset (-1): the first feature, the one farthest from it, the one farthest from their line.
  std::array<int, 3> features{-1, -1, -1};
};

// The certificate carried onto the measurement along the probed directions (artefact-frame
// coordinates, the first directionCount columns): measured ~ scale R calibrated + t.
struct AlignedArtefact {
  Eigen::MatrixXd deviations;  // per feature and probed direction: measured - aligned calibrated, mm
  Eigen::MatrixXd rotation;    // k x k
  Eigen::VectorXd translation;
  double scale = 1.0;
  std::array<int, 3> features{-1, -1, -1};  // the three-point alignment's features as used
};
// calibrated, measured: n x 3 in the artefact frame. Throws InvalidInput for three alignment
// features that do not span what the alignment needs (coincident, or on one line for a plane).
AlignedArtefact alignArtefact(const Eigen::MatrixX3d& calibrated, const Eigen::MatrixX3d& measured, ProbedDirections probed,
                              int dimension, const Alignment& alignment);

constexpr int kUncertaintyDraws = 400;  // U's own relative standard uncertainty 1 / sqrt(2 x 400) = 3.5 %

// The k = 2 uncertainty of each deviation (n x k, mm) by Monte Carlo over the alignment (GUM
// Supplement 1): each calibrated coordinate drawn with its feature's standard uncertainty and
// each measured one with the probe's (per probed direction), the alignment repeated; so the
// leverage of least squares and the three features of a three-point alignment are accounted
// for. Deterministic for a given seed.
Eigen::MatrixXd deviationUncertainty(const Eigen::MatrixX3d& calibrated, const Eigen::MatrixX3d& measured, ProbedDirections probed,
                                     int dimension, const Alignment& alignment, const Eigen::VectorXd& certificateSigma,
                                     const Vec3& probeSigma, int draws = kUncertaintyDraws, std::uint64_t seed = 1);

}  // namespace mtacc
