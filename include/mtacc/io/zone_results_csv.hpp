#pragma once
// Zone results of a cubic machining test (docs/file-formats.md "Zone results"): one row per
// measured zone, `zone,height_um[,slope_x_um_per_mm,slope_y_um_per_mm]`, heights in the
// measurement frame of seed 001 (referenced to zone I), and an optional '# noise: 0.2 um'
// line (the standard deviation of a height).
#include <optional>
#include <string>
#include <vector>

namespace mtacc {

struct ZoneMeasurement {
  std::string name;
  double height = 0;                     // mm
  std::optional<double> slopeX, slopeY;  // mm/mm
  int line = 0;
};

struct ZoneResults {
  std::string file;
  std::vector<ZoneMeasurement> zones;
  std::optional<double> noise;  // mm
};

// Throws InputError naming file, line and column.
ZoneResults readZoneResults(const std::string& path);
ZoneResults parseZoneResults(const std::string& text, const std::string& sourceName);
std::string zoneResultsCsv(const ZoneResults& results);

}  // namespace mtacc
