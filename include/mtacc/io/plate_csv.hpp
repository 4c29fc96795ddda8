#pragma once
// A hole- or ball-plate measurement (docs/file-formats.md "Plate measurements"): the plate, its
// placement on the machine, the temperatures, the probe, then one row per probed feature with
// its measured coordinates along the plate axes relative to the reference feature (0, 0):
//   # plate: 9 x 9, pitch 50 mm          rows x columns and pitch (required)
//   # features: all | outer              which features are probed (default all)
//   # origin: -350, -455, -160 mm         reference feature, workpiece frame (required)
//   # axes: 1,0,0 / 0,1,0                 plate u and v axes in the workpiece frame (default x / y)
//   # stylus: 0, 0, 60 mm                 probe tip relative to the TCP, tool frame (default 0)
//   # pose: B=0,C=0                       positions of the axes that stay, mm and deg (default: reference pose)
//   # temperatures: 20.8, 21.2, 20 C      scale, plate, reference (default all 20)
//   # expansion: 11.5e-6, 12e-6           scale and plate, 1/K (default 0)
//   # probe: 1.1, 0.8 um                  2S of the probe along u and v (for the budget)
//   # simulation: 6.3 um                  2S of the machine model's prediction (for the budget)
//   row,column,u,v                        measured mm
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mtacc/machine/machine.hpp"
#include "mtacc/measurement/plates.hpp"

namespace mtacc {

struct PlateMeasurement {
  std::string file;
  Plate plate;
  PlatePlacement placement;
  PlateTemperatures temperatures;
  std::optional<Eigen::Vector2d> probe;  // 2S, mm
  std::optional<double> simulation;      // 2S, mm
  std::vector<std::pair<int, int>> features;  // the reference first
  Eigen::MatrixX2d measured;             // mm, per feature
  int originLine = 0;                    // where the placement is given, for errors about it
  int plateLine = 0;                     // where the plate is given
};

// Throws InputError naming file, line and key: a missing or repeated feature (every feature of
// `features` once), a feature outside the plate, axes that are not orthonormal, values that
// are not finite or beyond ±10 mm of the nominal grid.
PlateMeasurement readPlateMeasurement(const Machine& machine, const std::string& path);
PlateMeasurement parsePlateMeasurement(const Machine& machine, const std::string& text, const std::string& sourceName);
// The header lines alone (no readings): the plate, placement, temperatures and 2S values.
PlateMeasurement parsePlateLayout(const Machine& machine, const std::string& text, const std::string& sourceName);
std::string plateMeasurementCsv(const Machine& machine, const PlateMeasurement& measurement);

}  // namespace mtacc
