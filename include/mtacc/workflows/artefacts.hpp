#pragma once
// Calibrated artefacts on a machine (docs/file-formats.md "Artefact measurements"): a measured
// step gauge, ball bar, plate or 3-D artefact against its certificate and against the machine's
// error model, each deviation with its k = 2 uncertainty; an artefact measurement simulated on
// the machine with its errors, written in the same format; one placement of an identification
// campaign (`plate-identify`).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/identification/plate_identification.hpp"
#include "mtacc/io/artefact_csv.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// The certificate and the measurement in artefact-frame coordinates, both corrected to the
// reference temperature (the certificate for the artefact's expansion, the readings for the
// scales'), mm.
struct ArtefactCoordinates {
  Eigen::MatrixX3d calibrated, measured;
};
ArtefactCoordinates artefactCoordinates(const ArtefactMeasurement& measurement);

struct ArtefactEvaluation {
  std::shared_ptr<const Machine> machine;
  ArtefactMeasurement measurement;
  JointMatrix poses;
  // Per feature and probed direction (u, v, w), mm: the measured deviations after the file's
  // alignment, the model's (the same alignment on the simulated probing), their difference.
  AlignedArtefact measured, simulated;
  Eigen::MatrixXd residual;
  // U (k = 2) of each measured deviation: combined, and from the certificate and the probe alone.
  Eigen::MatrixXd expanded, certificatePart, probingPart;
  std::optional<double> simulation;  // 2S of the model (the file's), mm
  int beyond = 0;                    // residual components beyond sqrt(U^2 + 2S_sim^2)
};
// Throws InputError naming the file, UnreachableInput naming the feature beyond the travel.
ArtefactEvaluation evaluateArtefact(const MachineSetup& setup, ArtefactMeasurement measurement);
ArtefactEvaluation evaluateArtefactFile(const MachineSetup& setup, const std::string& path);
// data: the artefact (or plate) measurement's file.
const OptionSchema& artefactEvaluationSchema();
// Deviations in um, positions in mm, rotations in urad, scale in ppm.
nlohmann::json toJson(const ArtefactEvaluation& evaluation);

// One placement of an identification campaign from a measured file: the readings after the
// temperature corrections and a least-squares rigid alignment (no scale: a scale is the
// machine's), weighted by the probe's 2S when the file states it.
CampaignPlacement campaignPlacement(const KinematicModel& nominal, const ArtefactMeasurement& measurement);

struct ArtefactSimulationRequest {
  std::string layout, output;  // the artefact file without measured values; the file to write
  std::string noise = "0 um";  // standard deviation of each measured coordinate
  std::uint64_t seed = 1;
};
const OptionSchema& artefactSimulationSchema();
ArtefactSimulationRequest artefactSimulationRequest(const OptionValues& values);
// The layout's features probed on the machine with its errors (each at its certificate place),
// written atomically to `output`; returns the measurement.
ArtefactMeasurement simulateArtefactFile(const MachineSetup& setup, const ArtefactSimulationRequest& request);

}  // namespace mtacc
