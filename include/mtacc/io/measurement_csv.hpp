#pragma once
// One measurement run per CSV file (docs/file-formats.md, "Measurement data"): '# key: value'
// lines give the instrument and its set-up, then a header row and one row per pose: the
// commanded axes (mm, deg), optional <axis>_dir columns, and the readings in um
// (ballbar: angle_deg, sense, dL_um; R-test and probe: dx_um, dy_um, dz_um; directional:
// d_um). A ballbar file may omit the axis columns when it names its circle (plane, centre,
// pose): the poses then follow from angle_deg, as for a ballbar's own export. Without
// 'set_at', the centre ball is set where the tool ball is with the target commanded.
#include <string>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

// Throws InputError naming the file, line and key or column.
MeasurementRun readMeasurementCsv(const KinematicModel& nominal, const std::string& path);
MeasurementRun parseMeasurementCsv(const KinematicModel& nominal, const std::string& text,
                                   const std::string& sourceName);
// The file's text; readings must be present.
std::string measurementCsv(const Machine& machine, const MeasurementRun& run);

}  // namespace mtacc
