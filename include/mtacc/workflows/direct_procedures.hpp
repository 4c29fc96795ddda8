#pragma once
// Workflows `squareness` and `yry`: two procedures of seed 003's direct measurements (the 1991
// BCR report, App. B) that turn readings into an error: the squareness of two axes from a
// calibrated square probed along both sides (App. B.5), and the Y axis's yaw yry from two
// straightness runs of a straightedge at two X positions (eq. B.2).
#include <nlohmann/json.hpp>

#include <vector>

#include "mtacc/core/option_schema.hpp"

namespace mtacc {

// aligned_to: x or z (the side the square is aligned to); alpha, beta: the slopes of the lines
// through the readings along that side and the other (arcsec); block: the square's own
// squareness (arcsec).
const OptionSchema& squarenessSchema();
struct SquarenessResult {
  char alignedTo;
  double alpha, beta, block, squareness;  // rad
};
SquarenessResult squarenessFromOptions(const OptionValues& options);
nlohmann::json toJson(const SquarenessResult& result);

// y (mm), ytz1 and ytz2 (um, one per y), xrx (arcsec, one, or one per y), x1 and x2 (mm).
const OptionSchema& yrySchema();
struct YryResult {
  double x1, x2;                        // mm
  std::vector<double> y, yry;           // mm, rad
};
YryResult yryFromOptions(const OptionValues& options);
nlohmann::json toJson(const YryResult& result);

}  // namespace mtacc
