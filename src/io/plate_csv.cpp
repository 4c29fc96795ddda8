#include "mtacc/io/plate_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr int kMostFeatures = 100;  // per side

std::vector<double> numbers(const std::string& text, size_t count, const std::string& key) {
  const auto parts = splitFields(text);
  if (parts.size() != count) throw InputError(InputLocation{"", 0, key}, fmt::format("expected {} comma-separated numbers", count));
  std::vector<double> out;
  for (const auto& p : parts) out.push_back(parseNumber(p, key));
  return out;
}

PlateMeasurement parse(const Machine& machine, const std::string& text, const std::string& source, bool layoutOnly) {
  PlateMeasurement m;
  m.file = source;
  m.placement.name = std::filesystem::path(source).stem().string();
  int n = 0;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  std::map<std::string, int> seen;
  bool plateGiven = false, originGiven = false, headerSeen = false;
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
          } else if (key == "origin") {
            m.placement.origin = parseLengths(value, key);
            m.originLine = n;
            originGiven = true;
          } else if (key == "axes") {
            const auto slash = value.find('/');
            if (slash == std::string::npos) fail(key, "expected 'ux,uy,uz / vx,vy,vz'");
            const Vec3 u = parseVector(trim(value.substr(0, slash)), key), v = parseVector(trim(value.substr(slash + 1)), key);
            if (std::abs(u.norm() - 1) > 1e-6 || std::abs(v.norm() - 1) > 1e-6 || std::abs(u.dot(v)) > 1e-6)
              fail(key, "the plate axes must be orthogonal unit vectors");
            m.placement.u = u;
            m.placement.v = v;
          } else if (key == "stylus") {
            m.placement.stylus = parseLengths(value, key);
          } else if (key == "pose") {
            m.placement.fixedAxes = parsePose(machine, value, key, true);
          } else if (key == "temperatures") {
            const auto t = numbers(value.substr(0, value.find_last_not_of(" C") + 1), 3, key);
            for (const double v : t)
              if (!(v > -50 && v < 100)) fail(key, "temperatures in deg C");
            m.temperatures.scale = t[0];
            m.temperatures.plate = t[1];
            m.temperatures.reference = t[2];
          } else if (key == "expansion") {
            const auto e = numbers(value, 2, key);
            for (const double v : e)
              if (!(std::abs(v) < 1e-3)) fail(key, "expansion coefficients in 1/K (e.g. 11.5e-6)");
            m.temperatures.scaleExpansion = e[0];
            m.temperatures.plateExpansion = e[1];
          } else if (key == "probe") {
            const auto twoS = parseLengthList(value, 2, key, "'2S_u, 2S_v um'", "0.8, 0.9 um");
            m.probe = Eigen::Vector2d(twoS[0], twoS[1]);
            if (!(m.probe->minCoeff() > 0.0 && m.probe->maxCoeff() < 1.0)) fail(key, "probe 2S from above 0 to 1 mm");
          } else if (key == "simulation") {
            m.simulation = parseQuantityAs(value, Dimension::Length, key);
            if (!(*m.simulation >= 0.0 && *m.simulation < 1.0)) fail(key, "a 2S from 0 to 1 mm");
          } else if (key != "note") {
            fail(key,
                 "unknown key (expected plate, features, origin, axes, stylus, pose, temperatures, expansion, probe, simulation, note)");
          }
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
        if (!originGiven) fail("origin", "give '# origin: x, y, z mm' (the reference feature in the workpiece frame) before the data");
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
  if (!originGiven) fail("origin", "missing '# origin: x, y, z mm' (the reference feature in the workpiece frame)");
  if (m.placement.fixedAxes.empty()) m.placement.fixedAxes = machine.referencePose;
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
  out += fmt::format("# origin: {}, {}, {} mm\n# axes: {},{},{} / {},{},{}\n", p.origin.x(), p.origin.y(),
                     p.origin.z(), p.u.x(), p.u.y(), p.u.z(), p.v.x(), p.v.y(), p.v.z());
  out += fmt::format("# stylus: {}, {}, {} mm\n", p.stylus.x(), p.stylus.y(), p.stylus.z());
  std::string pose;
  for (int a = 0; a < machine.commandedCount(); ++a)
    if (machine.axes[static_cast<size_t>(a)].isRotary() && !p.fixedAxes.empty())
      pose += fmt::format("{}{}={}", pose.empty() ? "" : ",", machine.axes[static_cast<size_t>(a)].name,
                          p.fixedAxes[static_cast<size_t>(a)] / kDeg);
  if (!pose.empty()) out += "# pose: " + pose + "\n";
  const auto& t = m.temperatures;
  out += fmt::format("# temperatures: {}, {}, {} C\n# expansion: {}, {}\n", t.scale, t.plate, t.reference, t.scaleExpansion,
                     t.plateExpansion);
  if (m.probe) out += fmt::format("# probe: {}, {} um\n", m.probe->x() * 1e3, m.probe->y() * 1e3);
  if (m.simulation) out += fmt::format("# simulation: {} um\n", *m.simulation * 1e3);
  out += "row,column,u,v\n";
  for (size_t k = 0; k < m.features.size(); ++k)
    out += fmt::format("{},{},{:.7f},{:.7f}\n", m.features[k].first, m.features[k].second, m.measured(static_cast<Eigen::Index>(k), 0),
                       m.measured(static_cast<Eigen::Index>(k), 1));
  return out;
}

}  // namespace mtacc
