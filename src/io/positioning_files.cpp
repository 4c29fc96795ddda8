#include "mtacc/io/positioning_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <optional>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr int kMostTargets = 100000;
constexpr int kMostCycles = 1000;

struct Unit {
  double scale;  // to mm or rad
  PositioningAxis axis;
};

std::optional<Unit> parseUnit(const std::string& text) {
  const auto q = parseQuantity("1 " + text);
  if (!q) return std::nullopt;
  return Unit{q->value, q->dimension == Dimension::Length ? PositioningAxis::Linear : PositioningAxis::Rotary};
}

struct Value {
  double value;  // in the file's unit
  int line;
};

// Readings gathered by (target index, cycle index), both 0-based, with the line of each.
struct Grid {
  std::vector<std::optional<Value>> targets;
  std::vector<std::vector<std::optional<Value>>> forward, backward;  // [target][cycle]
  void resize(size_t m, size_t n) {
    targets.assign(m, std::nullopt);
    forward.assign(m, std::vector<std::optional<Value>>(n));
    backward = forward;
  }
};

// Deviations in mm / rad from the gathered grid, rows sorted by target; values are positions
// (deviation = value - target) or deviations. `countsLine`: where the counts were declared.
PositioningTest assemble(const std::string& source, const Grid& g, const Unit& unit, bool valuesArePositions, const std::string& name,
                         int countsLine) {
  const auto fail = [&](const std::string& key, const std::string& what, int line = 0) {
    throw InputError(InputLocation{source, line, key}, what);
  };
  const size_t m = g.targets.size(), n = m ? g.forward[0].size() : 0;
  if (m < 2) fail("targets", fmt::format("{} target position(s): ISO 230-2 needs at least 2 (5 per metre)", m), countsLine);
  if (n < 2) fail("cycles", fmt::format("{} cycle(s): the repeatability needs at least 2 (ISO 230-2 asks for 5)", n), countsLine);
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return g.targets[a]->value < g.targets[b]->value; });
  const double largest = unit.axis == PositioningAxis::Linear ? 10.0 : 10.0 * kDeg;
  PositioningTest t;
  t.name = name;
  t.axis = unit.axis;
  t.forward.resize(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
  t.backward.resize(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
  for (size_t r = 0; r < m; ++r) {
    const size_t i = order[r];
    const Value& given = *g.targets[i];
    const double target = given.value * unit.scale;
    if (r > 0 && !(target > t.targets.back())) fail("target", fmt::format("target {:g} is given twice", given.value), given.line);
    t.targets.push_back(target);
    for (const auto& [rows, matrix, key] :
         {std::tuple{&g.forward, &t.forward, "forward"}, std::tuple{&g.backward, &t.backward, "backward"}}) {
      for (size_t j = 0; j < n; ++j) {
        const auto& v = (*rows)[i][j];
        if (!v) fail(key, fmt::format("no {} reading of cycle {} at target {:g} (given here)", key, j + 1, given.value), given.line);
        const double deviation = v->value * unit.scale - (valuesArePositions ? target : 0.0);
        if (!(std::abs(deviation) <= largest))
          fail(key,
               fmt::format("the {} deviation at target {:g}, cycle {} is beyond ±{} (a wrong unit or target?)", key, given.value, j + 1,
                           unit.axis == PositioningAxis::Linear ? "10 mm" : "10 deg"),
               v->line);
        (*matrix)(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) = deviation;
      }
    }
  }
  return t;
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

// KEY=value, KEY[i]=value, KEY[i,j]=value.
PositioningTest parseKeyForm(const std::string& text, const std::string& source) {
  int n = 0;
  std::map<std::string, std::string> scalars;
  std::map<std::string, int> scalarLines;
  struct Indexed {
    std::string key;
    int i, j, line;
    double value;
  };
  std::vector<Indexed> indexed;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  for (const auto& [lineNumber, line] : contentLines(text)) {
    n = lineNumber;
    if (line[0] == '#') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) fail("line", "expected KEY=value");
    std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    const auto open = key.find('[');
    if (open == std::string::npos) {
      if (key != "UNIT" && key != "CYCLES" && key != "POSITIONS" && key != "DEC" && key != "REF_PV" && key != "TEST_PV" &&
          key != "TGT_SET_PV")
        fail(key,
             "unknown key (expected UNIT, CYCLES, POSITIONS, DEC, REF_PV, TEST_PV, TGT_SET_PV, TGT_DATA[i], "
             "REF_DATA_FWD[i,j] or REF_DATA_BWD[i,j])");
      if (!scalars.emplace(key, value).second) fail(key, "given twice");
      scalarLines[key] = n;
      continue;
    }
    if (key.back() != ']') fail(key, "expected KEY[i] or KEY[i,j]");
    const std::string name = key.substr(0, open);
    const auto indices = splitFields(key.substr(open + 1, key.size() - open - 2));
    const size_t expected = name == "TGT_DATA" ? 1 : (name == "REF_DATA_FWD" || name == "REF_DATA_BWD") ? 2 : 0;
    if (expected == 0) fail(key, "unknown key (expected TGT_DATA[i], REF_DATA_FWD[i,j] or REF_DATA_BWD[i,j])");
    if (indices.size() != expected) fail(key, fmt::format("{} takes {} index(es)", name, expected));
    Indexed e{name, parseCount(indices[0], key, 1, kMostTargets), expected == 2 ? parseCount(indices[1], key, 1, kMostCycles) : 0, n, 0.0};
    try {
      e.value = parseNumber(value, key);
    } catch (const InputError& err) {
      fail(key, err.reason());
    }
    if (!(std::abs(e.value) <= kLargestLength)) fail(key, "value beyond the largest allowed");
    indexed.push_back(e);
  }
  n = 0;
  for (const char* required : {"UNIT", "CYCLES", "POSITIONS"})
    if (!scalars.count(required)) fail(required, std::string("missing ") + required + "=...");
  n = scalarLines["UNIT"];
  const auto unit = parseUnit(scalars["UNIT"]);
  if (!unit) fail("UNIT", "'" + scalars["UNIT"] + "' is not a unit of length or angle");
  const auto count = [&](const char* key, int most) {
    n = scalarLines[key];
    try {
      return parseCount(scalars[key], key, 1, most);
    } catch (const InputError& e) {
      throw InputError(InputLocation{source, n, key}, e.reason());
    }
  };
  const int positions = count("POSITIONS", kMostTargets);
  const int cycles = count("CYCLES", kMostCycles);
  Grid g;
  g.resize(static_cast<size_t>(positions), static_cast<size_t>(cycles));
  for (const auto& e : indexed) {
    n = e.line;
    const std::string key = e.j ? fmt::format("{}[{},{}]", e.key, e.i, e.j) : fmt::format("{}[{}]", e.key, e.i);
    if (e.i > positions) fail(key, fmt::format("position {} beyond POSITIONS={}", e.i, positions));
    if (e.j > cycles) fail(key, fmt::format("cycle {} beyond CYCLES={}", e.j, cycles));
    auto& slot = e.key == "TGT_DATA"       ? g.targets[static_cast<size_t>(e.i - 1)]
                 : e.key == "REF_DATA_FWD" ? g.forward[static_cast<size_t>(e.i - 1)][static_cast<size_t>(e.j - 1)]
                                           : g.backward[static_cast<size_t>(e.i - 1)][static_cast<size_t>(e.j - 1)];
    if (slot) fail(key, "given twice");
    slot = Value{e.value, e.line};
  }
  n = 0;
  for (size_t i = 0; i < g.targets.size(); ++i)
    if (!g.targets[i]) fail(fmt::format("TGT_DATA[{}]", i + 1), "missing: every position needs its target");
  return assemble(source, g, *unit, true, stem(source), positions < 2 ? scalarLines["POSITIONS"] : scalarLines["CYCLES"]);
}

// target,cycle,forward,backward with '# unit:', '# values:', '# name:'.
PositioningTest parseCsvForm(const std::string& text, const std::string& source) {
  int n = 0;
  std::optional<Unit> unit;
  bool positions = true, valuesGiven = false, headerSeen = false;
  int headerLine = 0;
  std::string name = stem(source);
  std::map<double, size_t> targetIndex;
  struct Row {
    double target;
    int cycle, line;
    double forward, backward;
  };
  std::vector<Row> rows;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        if (key == "unit") {
          if (unit) fail(key, "given twice");
          unit = parseUnit(value);
          if (!unit) fail(key, "'" + value + "' is not a unit of length or angle");
        } else if (key == "values") {
          if (valuesGiven) fail(key, "given twice");
          valuesGiven = true;
          if (value != "positions" && value != "deviations") fail(key, "expected 'positions' or 'deviations'");
          positions = value == "positions";
        } else if (key == "name") {
          name = value;
        } else if (key != "note") {
          fail(key, "unknown key (expected unit, values, name or note)");
        }
      },
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (!headerSeen) {
          if (fields != std::vector<std::string>{"target", "cycle", "forward", "backward"})
            fail("header", "expected the header 'target,cycle,forward,backward'");
          headerSeen = true;
          headerLine = n;
          return;
        }
        if (!unit) fail("unit", "give '# unit:' before the data (a length unit for a linear axis, an angle for a rotary one)");
        if (fields.size() != 4) fail("row", fmt::format("expected 4 fields, found {}", fields.size()));
        Row r{0, 0, n, 0, 0};
        try {
          r.target = parseNumber(fields[0], "target");
          r.cycle = parseCount(fields[1], "cycle", 1, kMostCycles);
          r.forward = parseNumber(fields[2], "forward");
          r.backward = parseNumber(fields[3], "backward");
        } catch (const InputError& e) {
          fail(e.where().key, e.reason());
        }
        for (const double v : {r.target, r.forward, r.backward})
          if (!(std::abs(v) <= kLargestLength)) fail("row", "value beyond the largest allowed");
        rows.push_back(r);
      });
  n = 0;
  if (!unit) fail("unit", "missing '# unit:' line (a length unit for a linear axis, an angle for a rotary one)");
  if (!headerSeen) fail("header", "no header row 'target,cycle,forward,backward'");
  int cycles = 0;
  for (const auto& r : rows) {
    targetIndex.emplace(r.target, targetIndex.size());
    cycles = std::max(cycles, r.cycle);
  }
  Grid g;
  g.resize(targetIndex.size(), static_cast<size_t>(cycles));
  for (const auto& r : rows)
    if (!g.targets[targetIndex[r.target]]) g.targets[targetIndex[r.target]] = Value{r.target, r.line};
  for (const auto& r : rows) {
    n = r.line;
    const size_t i = targetIndex[r.target], j = static_cast<size_t>(r.cycle - 1);
    if (g.forward[i][j]) fail("cycle", fmt::format("cycle {} at target {:g} is given twice", r.cycle, r.target));
    g.forward[i][j] = Value{r.forward, r.line};
    g.backward[i][j] = Value{r.backward, r.line};
  }
  n = 0;
  return assemble(source, g, *unit, positions, name, headerLine);
}

}  // namespace

PositioningTest parsePositioningTest(const std::string& text, const std::string& source) {
  // The key form has '=' on its first line that is not a comment; the CSV form never does.
  for (const auto& [lineNumber, line] : contentLines(text))
    if (line[0] != '#') return line.find('=') != std::string::npos ? parseKeyForm(text, source) : parseCsvForm(text, source);
  throw InputError(InputLocation{source, 0, ""}, "no data: expected ISO 230-2 KEY=value lines or a CSV 'target,cycle,forward,backward'");
}

PositioningTest readPositioningTest(const std::string& path) { return parsePositioningTest(readTextFile(path), path); }

}  // namespace mtacc
