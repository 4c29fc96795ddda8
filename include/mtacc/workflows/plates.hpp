#pragma once
// Hole and ball plates on a machine (seed 003 §5.3): a measured plate against the machine's
// error model, with the residual and its k = 2 bound; a plate measurement simulated on the
// machine with its errors, written in the same format.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/identification/plate_identification.hpp"
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
// data: the plate measurement's file.
const OptionSchema& plateComparisonSchema();
// Deviations in um, positions in mm.
nlohmann::json toJson(const PlateComparison& comparison);

// The plate and its placement as the front ends take them: each field as a plate file's header
// states it (docs/file-formats.md "Plate measurements"), read by that file's own reader.
struct PlateLayoutFields {
  std::string plate = "9 x 9, pitch 50 mm", features = "all";
  std::string origin;  // the reference feature in the workpiece frame, e.g. "-350, -455, -160 mm"
  std::string axes = "1,0,0 / 0,1,0", stylus = "0,0,0 mm";
  std::string pose, probe, simulation;  // optional: the axes that stay; 2S of the probe (u, v) and of the model to state
};
// The field named `key` (plate, features, origin, axes, stylus, pose, probe, simulation); throws
// InputError naming another key.
std::string& plateLayoutField(PlateLayoutFields& fields, const std::string& key);
struct PlateSimulationRequest {
  std::string output;
  PlateLayoutFields layout;
  std::string noise = "0 um";  // standard deviation of a coordinate
  std::uint64_t seed = 1;
};
// The measurement the machine with its errors would give (features at their nominal places),
// written atomically to `output`; returns it.
PlateMeasurement simulatePlateFile(const MachineSetup& setup, const PlateSimulationRequest& request);
// The options of `simulate plate`: output, the layout's fields by their names, noise, seed.
const OptionSchema& plateSimulationSchema();
PlateSimulationRequest plateSimulationRequest(const OptionValues& values);

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

// The options of `plate-identify`, declared once, and what they give.
struct PlateIdentificationRequest {
  std::vector<std::string> files;  // one plate measurement per placement
  double pieceLength = 100.0;      // mm
};
const OptionSchema& plateIdentificationSchema();
PlateIdentificationRequest plateIdentificationRequest(const OptionValues& values);
nlohmann::json toJson(const PlateIdentificationStudy& study);

}  // namespace mtacc
