#include "mtacc/io/cone_points_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "measured_point_limits.hpp"

namespace mtacc {
namespace {

constexpr size_t kMostPoints = 1000000;

}  // namespace

ConePoints parseConePoints(const std::string& text, const std::string& source) {
  ConePoints out;
  int n = 0;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  bool headerSeen = false;
  size_t count = 0;
  std::map<std::pair<std::string, std::string>, std::pair<size_t, int>> sections;  // (element, name) -> index, last line
  readCommentedLines(
      text, n, [&](const std::string&, const std::string&) {},
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (!headerSeen) {
          if (fields != std::vector<std::string>{"element", "section", "x", "y", "z"}) fail("header", "expected the header 'element,section,x,y,z'");
          headerSeen = true;
          return;
        }
        if (fields.size() != 5) fail("row", fmt::format("expected 5 fields, found {}", fields.size()));
        if (++count > kMostPoints) fail("row", fmt::format("at most {} points", kMostPoints));
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
          const char* key = k == 0 ? "x" : k == 1 ? "y" : "z";
          try {
            p[k] = parseNumber(fields[static_cast<size_t>(2 + k)], key);
          } catch (const InputError& e) {
            fail(key, e.reason());
          }
          if (!(std::abs(p[k]) <= kLargestMeasuredCoordinate)) fail(key, fmt::format("within +-{} mm", kLargestMeasuredCoordinate));
        }
        const std::string& element = fields[0];
        if (element == "plane") {
          out.plane.push_back(p);
          return;
        }
        if (element != "cone" && element != "cylinder") fail("element", "expected plane, cylinder or cone, got '" + element + "'");
        if (fields[1].empty()) fail("section", "a cone or cylinder point needs its section");
        auto& list = element == "cone" ? out.cone : out.cylinder;
        auto [it, fresh] = sections.emplace(std::pair{element, fields[1]}, std::pair{list.size(), n});
        if (fresh) list.push_back({fields[1], {}});
        it->second.second = n;
        list[it->second.first].points.push_back(p);
      });
  n = 0;
  if (!headerSeen) fail("header", "no header row 'element,section,x,y,z'");
  if (out.cone.empty()) fail("element", "no cone section");
  for (const auto& [key, where] : sections) {
    const auto& list = key.first == "cone" ? out.cone : out.cylinder;
    n = where.second;
    if (list[where.first].points.size() < 4)
      fail("section", fmt::format("{} section '{}' has {} points (at least four)", key.first, key.second, list[where.first].points.size()));
    try {
      fitCircle(list[where.first].points, Vec3::UnitZ());
    } catch (const InvalidInput& e) {
      fail("section", fmt::format("{} section '{}': {}", key.first, key.second, e.what()));
    }
  }
  n = 0;
  if (!out.plane.empty() && out.plane.size() < 3) fail("element", "plane A needs at least three points");
  return out;
}

ConePoints readConePoints(const std::string& path) { return parseConePoints(readTextFile(path), path); }

}  // namespace mtacc
