#pragma once
// Hole and ball plates on a machine (seed 003 §5.3): a measured plate against the machine's
// error model, with the residual and its k = 2 bound; a plate measurement simulated on the
// machine with its errors, written in the same format.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "mtacc/io/plate_csv.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct PlateComparison {
  std::shared_ptr<const Machine> machine;
  PlateMeasurement measurement;
  PlatePoses poses;
  std::vector<Eigen::Vector2d> nominal;  // feature positions relative to the reference feature, mm
  // Per feature (u, v), mm, each with its misalignment removed: measured d_h (after the
  // temperature corrections), the model's D_h, and the residual d_h - D_h.
  Eigen::MatrixX2d measured, simulated, residual;
  std::optional<double> bound;  // k = 2 bound of a residual component (with probe and simulation 2S given)
  int beyond = 0;               // residual components beyond the bound
};

// Throws InputError naming the file, UnreachablePose naming the feature.
PlateComparison comparePlateFile(const MachineSetup& setup, const std::string& path);
// Deviations in um, positions in mm.
nlohmann::json toJson(const PlateComparison& comparison);

struct PlateSimulationRequest {
  std::string output;
  PlateMeasurement layout;      // plate, placement, temperatures, probe and simulation 2S to write; no readings
  std::string noise = "0 um";  // standard deviation of a coordinate
  std::uint64_t seed = 1;
};
// The measurement the machine with its errors would give (features at their nominal places),
// written atomically to `output`; returns it.
PlateMeasurement simulatePlateFile(const MachineSetup& setup, const PlateSimulationRequest& request);

// The component functions of X, Y, Z (C1 piecewise, pieces of about `pieceLength` mm) and the
// squareness identified from measured plates (seed 003 §7.7): each file one placement, read
// with its temperatures corrected, weighted by its probe's 2S (or unweighted when no file states
// it), a translation and rotation per plate; with the observability report naming what the set
// of plates cannot determine, and the identified functions as the machine YAML's errors.
struct PlateIdentificationStudy {
  std::shared_ptr<const Machine> machine;
  std::vector<std::string> files;
  ErrorModel identified;  // the shape with the estimates (undetermined parameters at the minimum-norm value)
  std::vector<Parameter> parameters;
  PlateIdentification result;
  bool weighted = false;  // by the files' probe 2S: result.sigma is then the residual over that noise (~1), else in mm
  std::string yaml;
};
PlateIdentificationStudy identifyPlateFiles(const MachineSetup& setup, const std::vector<std::string>& files, double pieceLength = 100.0);
nlohmann::json toJson(const PlateIdentificationStudy& study);

}  // namespace mtacc
