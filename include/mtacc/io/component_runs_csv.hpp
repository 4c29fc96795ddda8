#pragma once
// Direct-measurement runs of one component error (docs/file-formats.md "Component runs"):
// '# component:', '# unit:' and optional '# instrument:', '# uncertainty:', '# abbe_offset:',
// '# expansion:', '# reference_temperature:', '# note:' lines, then rows
// `position,run,direction,value[,time_s][,temperature_C]`, direction 1 (forward) or -1.
#include <optional>
#include <string>

#include "mtacc/core/transform.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/measurement/direct_measurement.hpp"

namespace mtacc {

struct ComponentRunsFile {
  std::string file;
  std::string componentName;   // as written
  MotionComponent component;
  std::string instrument;
  std::optional<double> uncertainty;  // standard uncertainty of one reading, mm or rad
  std::optional<Vec3> abbeOffset;     // mm: measuring point relative to the carriage centroid
  std::optional<double> expansion;    // 1/K, with the temperature column
  double referenceTemperature = 20.0; // deg C
  ComponentRuns runs;
  Eigen::MatrixXd forwardTemperature, backwardTemperature;  // deg C, or empty
};

// Throws InputError naming file, line and key: an unknown component, a unit of the wrong kind,
// a row given twice, a run missing a direction or a position the other runs have (ragged), fewer
// than 2 runs, positions beyond the axis travel, values that are not finite or beyond ±10 mm/±10°.
ComponentRunsFile readComponentRuns(const Machine& machine, const std::string& path);
ComponentRunsFile parseComponentRuns(const Machine& machine, const std::string& text, const std::string& sourceName);
// The file's text: values in um (translations) or arcsec (rotations), positions in mm or deg,
// with times when the runs have them.
std::string componentRunsCsv(const Machine& machine, const ComponentRunsFile& file);

}  // namespace mtacc
