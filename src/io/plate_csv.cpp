#include "mtacc/io/plate_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/probing_header.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr int kMostFeatures = 100;  // per side

PlateMeasurement parse(const Machine& machine, const std::string& text, const std::string& source, bool layoutOnly) {
  PlateMeasurement m;
  m.file = source;
  m.placement.name = std::filesystem::path(source).stem().string();
  int n = 0;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  std::map<std::string, int> seen;
  ProbingHeader header;
  bool plateGiven = false, headerSeen = false;
  int headerLine = 0;
  std::map<std::pair<int, int>, std::pair<Eigen::Vector2d, int>> rows;
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        if (key != "note" && !seen.emplace(key, n).second) fail(key, fmt::format("given twice (first on line {})", seen[key]));
        try {
          if (key == "plate") {
            // "9 x 9, pitch 50 mm"
            int rowsCount = 0, columns = 0;
            char pitchText[64] = {0};
            if (std::sscanf(value.c_str(), "%d x %d, pitch %63[^\n]", &rowsCount, &columns, pitchText) != 3)
              fail(key, "expected 'ROWS x COLUMNS, pitch P mm'");
            if (rowsCount < 2 || columns < 2 || rowsCount > kMostFeatures || columns > kMostFeatures)
              fail(key, fmt::format("2 to {} rows and columns", kMostFeatures));
            m.plate.rows = rowsCount;
            m.plate.columns = columns;
            m.plate.pitch = parseQuantityAs(trim(pitchText), Dimension::Length, key);
            if (!(m.plate.pitch >= 1.0 && m.plate.pitch <= 1000.0)) fail(key, "a pitch from 1 to 1000 mm");
            plateGiven = true;
            m.plateLine = n;
          } else if (key == "features") {
            if (value != "all" && value != "outer") fail(key, "expected 'all' or 'outer'");
            m.placement.features = value == "all" ? PlateFeatures::All : PlateFeatures::Outer;
          } else if (key != "note" && !readProbingKey(machine, key, value, n, header)) {
            fail(key,
                 "unknown key (expected plate, features, origin, axes, stylus, pose, temperatures, expansion, probe, simulation, note)");
          }
          if (key == "probe" && header.probe.size() != 2) fail(key, "expected '2S_u, 2S_v um'");
        } catch (const InputError& e) {
          if (!e.where().file.empty()) throw;
          fail(key, e.reason());
        }
      },
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (!headerSeen) {
          if (fields != std::vector<std::string>{"row", "column", "u", "v"}) fail("header", "expected the header 'row,column,u,v'");
          headerSeen = true;
          headerLine = n;
          return;
        }
        if (!plateGiven) fail("plate", "give '# plate: ROWS x COLUMNS, pitch P mm' before the data");
        if (!header.originGiven) fail("origin", "give '# origin: x, y, z mm' (the reference feature in the workpiece frame) before the data");
        if (fields.size() != 4) fail("row", fmt::format("expected 4 fields, found {}", fields.size()));
        int row = 0, column = 0;
        Eigen::Vector2d uv;
        try {
          row = parseCount(fields[0], "row", 0, m.plate.rows - 1);
          column = parseCount(fields[1], "column", 0, m.plate.columns - 1);
          uv = {parseNumber(fields[2], "u"), parseNumber(fields[3], "v")};
        } catch (const InputError& e) {
          fail(e.where().key, e.reason());
        }
        if (!((uv - m.plate.centre(row, column)).cwiseAbs().maxCoeff() <= 10.0))
          fail("u", fmt::format("feature ({}, {}) measured more than 10 mm from its nominal place", row, column));
        if (!rows.emplace(std::pair{row, column}, std::pair{uv, n}).second)
          fail("row", fmt::format("feature ({}, {}) is given twice", row, column));
      });
  n = 0;
  if (!plateGiven) fail("plate", "missing '# plate: ROWS x COLUMNS, pitch P mm'");
  if (!header.originGiven) fail("origin", "missing '# origin: x, y, z mm' (the reference feature in the workpiece frame)");
  m.placement.origin = header.origin;
  m.originLine = header.originLine;
  m.placement.u = header.u;
  m.placement.v = header.v;
  m.placement.stylus = header.stylus;
  m.placement.fixedAxes = header.pose.empty() ? machine.referencePose : header.pose;
  m.temperatures = header.temperatures;
  if (!header.probe.empty()) m.probe = Eigen::Vector2d(header.probe[0], header.probe[1]);
  m.simulation = header.simulation;
  if (layoutOnly) return m;
  if (!headerSeen) fail("header", "no header row 'row,column,u,v'");
  // Every feature of the probed set once, in the order of platePoses (the reference first).
  std::set<std::pair<int, int>> expected;
  for (int r = 0; r < m.plate.rows; ++r)
    for (int c = 0; c < m.plate.columns; ++c)
      if (m.placement.features == PlateFeatures::All || r == 0 || c == 0 || r == m.plate.rows - 1 || c == m.plate.columns - 1) {
        expected.insert({r, c});
        if (!rows.count({r, c})) {
          n = headerLine;
          fail("row", fmt::format("feature ({}, {}) is missing from the table", r, c));
        }
        m.features.emplace_back(r, c);
      }
  for (const auto& [feature, value] : rows)
    if (!expected.count(feature)) {
      n = value.second;
      fail("row", fmt::format("feature ({}, {}) is not on the outer ring ('# features: outer')", feature.first, feature.second));
    }
  m.measured.resize(static_cast<Eigen::Index>(m.features.size()), 2);
  for (size_t k = 0; k < m.features.size(); ++k) m.measured.row(static_cast<Eigen::Index>(k)) = rows.at(m.features[k]).first.transpose();
  return m;
}

}  // namespace

PlateMeasurement parsePlateMeasurement(const Machine& machine, const std::string& text, const std::string& source) {
  return parse(machine, text, source, false);
}

PlateMeasurement parsePlateLayout(const Machine& machine, const std::string& text, const std::string& source) {
  return parse(machine, text, source, true);
}

PlateMeasurement readPlateMeasurement(const Machine& machine, const std::string& path) {
  return parsePlateMeasurement(machine, readTextFile(path), path);
}

std::string plateMeasurementCsv(const Machine& machine, const PlateMeasurement& m) {
  const auto& p = m.placement;
  std::string out = fmt::format("# plate: {} x {}, pitch {} mm\n# features: {}\n", m.plate.rows, m.plate.columns, m.plate.pitch,
                                p.features == PlateFeatures::All ? "all" : "outer");
  ProbingHeader header{.origin = p.origin, .u = p.u, .v = p.v, .stylus = p.stylus, .pose = p.fixedAxes, .temperatures = m.temperatures,
                       .probe = {}, .simulation = m.simulation};
  if (m.probe) header.probe = {m.probe->x(), m.probe->y()};
  out += probingHeaderText(machine, header);
  out += "row,column,u,v\n";
  for (size_t k = 0; k < m.features.size(); ++k)
    out += fmt::format("{},{},{:.7f},{:.7f}\n", m.features[k].first, m.features[k].second, m.measured(static_cast<Eigen::Index>(k), 0),
                       m.measured(static_cast<Eigen::Index>(k), 1));
  return out;
}

}  // namespace mtacc
