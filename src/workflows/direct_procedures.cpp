#include "mtacc/workflows/direct_procedures.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/measurement/direct_measurement.hpp"

namespace mtacc {

const OptionSchema& squarenessSchema() {
  static const OptionSchema schema{
      "squareness",
      {{.key = "aligned_to", .kind = OptionKind::Text,
        .help = "x (Z or Y w.r.t. X, App. B.5 L4656-4711) or z (Y w.r.t. Z, L4730-4741): the axis the square is aligned to",
        .required = true},
       {.key = "alpha", .kind = OptionKind::Number, .help = "slope of the line through the readings along the aligned side [arcsec]",
        .low = -36000, .high = 36000, .outOfRange = "must be within +-36000 arcsec", .required = true},
       {.key = "beta", .kind = OptionKind::Number, .help = "slope of the line through the readings along the other side [arcsec]",
        .low = -36000, .high = 36000, .outOfRange = "must be within +-36000 arcsec", .required = true},
       {.key = "block", .kind = OptionKind::Number, .help = "the square's own squareness, from its certificate [arcsec]", .defaultText = "0",
        .low = -36000, .high = 36000, .outOfRange = "must be within +-36000 arcsec"}}};
  return schema;
}

SquarenessResult squarenessFromOptions(const OptionValues& options) {
  const OptionReader read(squarenessSchema(), options);
  const std::string aligned = *read.text("aligned_to");
  if (aligned != "x" && aligned != "z") throw InputError({"", 0, "aligned_to"}, "expected x or z, got '" + aligned + "'");
  SquarenessResult r{aligned[0], *read.number("alpha") * kArcsec, *read.number("beta") * kArcsec, *read.number("block") * kArcsec, 0.0};
  r.squareness = squarenessFromBlock(r.alpha, r.beta, r.block, aligned == "x" ? kBlockAlignedToX : kBlockAlignedToZ);
  return r;
}

nlohmann::json toJson(const SquarenessResult& r) {
  return {{"aligned_to", std::string(1, r.alignedTo)},
          {"alpha_arcsec", r.alpha / kArcsec},
          {"beta_arcsec", r.beta / kArcsec},
          {"block_arcsec", r.block / kArcsec},
          {"squareness_arcsec", r.squareness / kArcsec},
          {"rule", r.alignedTo == 'x' ? "-alpha - beta + block" : "alpha - beta - block"}};
}

const OptionSchema& yrySchema() {
  const auto positions = [](const char* key, const char* help) {
    return OptionField{.key = key, .kind = OptionKind::Numbers, .help = help, .low = -1e5, .high = 1e5,
                       .outOfRange = "must be within +-100000", .required = true};
  };
  static const OptionSchema schema{
      "yry",
      {positions("y", "Y positions of the readings [mm]"),
       positions("ytz1", "straightness readings (z) along Y with the X carriage at x1, one per y [um]"),
       positions("ytz2", "the same with the X carriage at x2 [um]"),
       positions("xrx", "the X axis's roll between the set-ups, one value or one per y [arcsec]"),
       {.key = "x1", .kind = OptionKind::Number, .help = "X position of the first set-up [mm]", .low = -1e5, .high = 1e5,
        .outOfRange = "must be within +-100000 mm", .required = true},
       {.key = "x2", .kind = OptionKind::Number, .help = "X position of the second set-up [mm]", .low = -1e5, .high = 1e5,
        .outOfRange = "must be within +-100000 mm", .required = true}}};
  return schema;
}

YryResult yryFromOptions(const OptionValues& options) {
  const OptionReader read(yrySchema(), options);
  YryResult r{*read.number("x1"), *read.number("x2"), read.numbers("y"), {}};
  const auto ytz1 = read.numbers("ytz1"), ytz2 = read.numbers("ytz2"), xrx = read.numbers("xrx");
  const size_t n = r.y.size();
  if (ytz1.size() != n) throw InputError({"", 0, "ytz1"}, fmt::format("{} readings for {} positions", ytz1.size(), n));
  if (ytz2.size() != n) throw InputError({"", 0, "ytz2"}, fmt::format("{} readings for {} positions", ytz2.size(), n));
  if (xrx.size() != 1 && xrx.size() != n) throw InputError({"", 0, "xrx"}, fmt::format("{} values: give one, or one per position ({})", xrx.size(), n));
  if (std::abs(r.x1 - r.x2) < 1.0) throw InputError({"", 0, "x2"}, "the two set-ups must be at least 1 mm apart in X (the arm of eq. B.2)");
  for (size_t i = 0; i < n; ++i)
    r.yry.push_back(yryFromStraightness(ytz1[i] * 1e-3, ytz2[i] * 1e-3, r.y[i], xrx[xrx.size() == 1 ? 0 : i] * kArcsec, r.x1, r.x2));
  return r;
}

nlohmann::json toJson(const YryResult& r) {
  nlohmann::json j{{"x1_mm", r.x1}, {"x2_mm", r.x2}, {"y_mm", r.y}, {"yry_arcsec", nlohmann::json::array()}};
  for (double v : r.yry) j["yry_arcsec"].push_back(v / kArcsec);
  return j;
}

}  // namespace mtacc
