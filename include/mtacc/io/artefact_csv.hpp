#pragma once
// A calibrated artefact measured on the machine (docs/file-formats.md "Artefact measurements"):
// the artefact, its placement, how it was probed and aligned, the shared probing header
// (io/probing_header.hpp), then one row per feature with its certificate position in the
// artefact frame, the certificate's expanded uncertainty and its measured position:
//   # artefact: KOBA step gauge 1020      a name (required)
//   # dimension: 1                        1 along u, 2 in the u-v plane, 3 anywhere (required)
//   # origin: -300, -200, -150 mm         the artefact frame's origin, workpiece frame (required)
//   # probed: all | in-plane | along      the directions a reading measures (default all)
//   # alignment: least-squares | least-squares-scaled | three-point [A, B, C]
//   # certificate: 0.7 um                 U (k = 2) of a calibrated coordinate without its own
//   feature,u,v,w,U,x,y,z                 mm (U in um, may be empty); x,y,z empty in a layout
#include <optional>
#include <string>
#include <vector>

#include "mtacc/io/probing_header.hpp"
#include "mtacc/io/plate_csv.hpp"
#include "mtacc/measurement/artefact.hpp"

namespace mtacc {

struct ArtefactMeasurement {
  std::string file;
  Artefact artefact;
  ArtefactPlacement placement;
  PlateTemperatures temperatures;
  Alignment alignment;
  std::vector<double> probe;          // 2S per probed direction, mm; empty: not stated
  std::optional<double> simulation;   // 2S of the model's prediction, mm
  bool certificateStated = false;     // every feature's uncertainty given (its own or the default)
  Eigen::MatrixX3d measured;          // per feature, workpiece frame, mm; no rows: a layout
  int originLine = 0, artefactLine = 0, alignmentLine = 0;
  std::vector<int> featureLines;      // per feature, where the table gives it
};

// Throws InputError naming file, line and key: a feature given twice, a certificate without a
// measured value, a feature off the declared line or plane, values not finite or beyond 10 mm
// of the placed certificate, alignment features that are not in the table.
ArtefactMeasurement parseArtefactMeasurement(const Machine& machine, const std::string& text, const std::string& sourceName);
ArtefactMeasurement readArtefactMeasurement(const Machine& machine, const std::string& path);
// Every number at full precision (the positions to 1e-10 mm).
std::string artefactMeasurementCsv(const Machine& machine, const ArtefactMeasurement& measurement);
// A regular-grid plate file in the artefact form: features "row,column" at (u, v, 0), probed in
// its plane, aligned by least squares, the measured positions carried into the workpiece frame.
ArtefactMeasurement artefactFromPlate(const PlateMeasurement& plate);
// Either file form, told apart by its first header key ("# plate:" or "# artefact:").
ArtefactMeasurement readArtefactOrPlate(const Machine& machine, const std::string& path);

}  // namespace mtacc
