#include "mtacc/io/zone_results_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr double kLargestHeight = 10.0;  // mm: a zone result beyond is a unit mistake
constexpr double kLargestSlope = 1.0;    // mm/mm

}  // namespace

ZoneResults parseZoneResults(const std::string& text, const std::string& source) {
  ZoneResults r;
  r.file = source;
  int n = 0;
  std::vector<std::string> header;
  std::set<std::string> seen;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        if (key != "noise" && key != "note") fail(key, "unknown key (expected noise or note)");
        if (key == "noise") {
          if (r.noise) fail(key, "given twice");
          try {
            r.noise = parseQuantityAs(value, Dimension::Length, "noise");
          } catch (const InputError& e) {
            fail("noise", e.reason());
          }
          if (!(*r.noise >= 1e-6 && *r.noise <= 1.0)) fail("noise", "the height noise must be from 1 nm to 1 mm");
        }
      },
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (header.empty()) {
          header = fields;
          const bool heights = header.size() == 2, tilts = header.size() == 4;
          if (!((heights || tilts) && header[0] == "zone" && header[1] == "height_um" &&
                (heights || (header[2] == "slope_x_um_per_mm" && header[3] == "slope_y_um_per_mm"))))
            fail("header", "expected 'zone,height_um' or 'zone,height_um,slope_x_um_per_mm,slope_y_um_per_mm'");
          return;
        }
        if (fields.size() != header.size()) fail("row", fmt::format("expected {} fields, found {}", header.size(), fields.size()));
        ZoneMeasurement z;
        z.name = fields[0];
        z.line = n;
        if (z.name.empty()) fail("zone", "empty zone name");
        if (!seen.insert(z.name).second) fail("zone", "zone '" + z.name + "' is given twice");
        const auto number = [&](size_t k, double largest) {
          double v = 0;
          try {
            v = parseNumber(fields[k], header[k]);
          } catch (const InputError& e) {
            fail(header[k], e.reason());
          }
          if (!(std::abs(v) * 1e-3 <= largest)) fail(header[k], fmt::format("must be within +-{:g} (a unit mistake?)", largest * 1e3));
          return v * 1e-3;
        };
        z.height = number(1, kLargestHeight);
        if (header.size() == 4) {
          z.slopeX = number(2, kLargestSlope);
          z.slopeY = number(3, kLargestSlope);
        }
        r.zones.push_back(z);
      });
  if (header.empty()) fail("header", "no header row 'zone,height_um[,slope_x_um_per_mm,slope_y_um_per_mm]'");
  if (r.zones.empty()) fail("row", "no zone results");
  return r;
}

ZoneResults readZoneResults(const std::string& path) { return parseZoneResults(readTextFile(path), path); }

std::string zoneResultsCsv(const ZoneResults& r) {
  const bool slopes = std::all_of(r.zones.begin(), r.zones.end(), [](const auto& z) { return z.slopeX && z.slopeY; });
  std::string out = "# zone results of a cubic machining test, referenced to the reference zone (mtacc cubic)\n";
  if (r.noise) out += fmt::format("# noise: {:.9g} um\n", *r.noise * 1e3);
  out += slopes ? "zone,height_um,slope_x_um_per_mm,slope_y_um_per_mm\n" : "zone,height_um\n";
  for (const auto& z : r.zones)
    out += slopes ? fmt::format("{},{:.6f},{:.6f},{:.6f}\n", z.name, z.height * 1e3, *z.slopeX * 1e3, *z.slopeY * 1e3)
                  : fmt::format("{},{:.6f}\n", z.name, z.height * 1e3);
  return out;
}

}  // namespace mtacc
