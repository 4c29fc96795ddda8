#include "mtacc/io/component_runs_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr int kMostRuns = 1000;

struct RunReading {
  double value, time, temperature;
  int line;
};

}  // namespace

ComponentRunsFile parseComponentRuns(const Machine& machine, const std::string& text, const std::string& source) {
  ComponentRunsFile f;
  f.file = source;
  int n = 0;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  std::map<std::string, int> seen;
  std::optional<double> unit;
  std::vector<std::string> header;
  // (run, direction) -> position -> reading
  std::map<std::pair<int, int>, std::map<double, RunReading>> runs;
  bool componentGiven = false;
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        if (key != "note" && !seen.emplace(key, n).second) fail(key, fmt::format("given twice (first on line {})", seen[key]));
        if (key == "component") {
          const auto c = findMotionComponent(machine, value);
          if (!c) fail(key, "'" + value + "' is not a component error of this machine (e.g. EXX, xtx, EAX, xrx)");
          f.componentName = value;
          f.component = *c;
          componentGiven = true;
        } else if (key == "unit") {
          if (!componentGiven) fail(key, "give '# component:' before '# unit:'");
          const Dimension dim = f.component.component < 3 ? Dimension::Length : Dimension::Angle;
          const auto q = parseQuantity("1 " + value);
          if (!q || q->dimension != dim) fail(key, "'" + value + "' is not a unit of " + withArticle(dim) + " (the component's)");
          unit = q->value;
        } else if (key == "instrument") {
          f.instrument = value;
        } else if (key == "uncertainty" || key == "abbe_offset") {
          if (!componentGiven) fail(key, "give '# component:' first");
          try {
            if (key == "uncertainty") {
              f.uncertainty = parseQuantityAs(value, f.component.component < 3 ? Dimension::Length : Dimension::Angle, key);
              if (!(*f.uncertainty > 0.0)) fail(key, "must be positive");
            } else {
              if (f.component.component >= 3) fail(key, "an Abbe offset applies to a translation component");
              f.abbeOffset = parseLengths(value, key);
            }
          } catch (const InputError& e) {
            fail(key, e.reason());
          }
        } else if (key == "expansion") {
          try {
            f.expansion = parseNumber(value, key);
          } catch (const InputError& e) {
            fail(key, e.reason());
          }
          if (!(std::abs(*f.expansion) < 1e-3)) fail(key, "an expansion coefficient in 1/K (e.g. 11.5e-6)");
        } else if (key == "reference_temperature") {
          try {
            f.referenceTemperature = parseNumber(value, key);
          } catch (const InputError& e) {
            fail(key, e.reason());
          }
          if (!(f.referenceTemperature > -50 && f.referenceTemperature < 100)) fail(key, "a temperature in deg C");
        } else if (key != "note") {
          fail(key, "unknown key (expected component, unit, instrument, uncertainty, abbe_offset, expansion, reference_temperature, note)");
        }
      },
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (header.empty()) {
          header = fields;
          const bool ok =
              header.size() >= 4 && header[0] == "position" && header[1] == "run" && header[2] == "direction" && header[3] == "value";
          std::set<std::string> extra(header.begin() + std::min<size_t>(4, header.size()), header.end());
          if (!ok || extra.size() != header.size() - 4 ||
              !std::all_of(extra.begin(), extra.end(), [](const std::string& c) { return c == "time_s" || c == "temperature_C"; }))
            fail("header", "expected 'position,run,direction,value' and optionally 'time_s', 'temperature_C'");
          return;
        }
        if (fields.size() != header.size()) fail("row", fmt::format("expected {} fields, found {}", header.size(), fields.size()));
        if (!unit) fail("unit", "missing '# unit:' before the data (the unit of the values)");
        double position = 0, value = 0, time = NAN, temperature = NAN;
        int run = 0, direction = 0;
        try {
          position = parseNumber(fields[0], "position");
          run = parseCount(fields[1], "run", 1, kMostRuns);
          direction = parseCount(fields[2], "direction", -1, 1);
          value = parseNumber(fields[3], "value") * *unit;
          for (size_t k = 4; k < fields.size(); ++k) (header[k] == "time_s" ? time : temperature) = parseNumber(fields[k], header[k]);
        } catch (const InputError& e) {
          fail(e.where().key, e.reason());
        }
        if (direction == 0) fail("direction", "1 (forward) or -1 (backward)");
        const Axis& axis = machine.axes[static_cast<size_t>(f.component.axis)];
        if (axis.isRotary()) position *= kDeg;
        if (axis.travel && (position < axis.travel->min - 1e-9 || position > axis.travel->max + 1e-9))
          fail("position", fmt::format("{} is beyond the travel of {}", fields[0], axis.name));
        const double largest = f.component.component < 3 ? 10.0 : 10.0 * kDeg;
        if (!(std::abs(value) <= largest)) fail("value", "beyond ±10 mm or ±10° (a wrong unit?)");
        if (!std::isnan(temperature) && !(temperature > -50 && temperature < 100)) fail("temperature_C", "a temperature in deg C");
        if (!std::isnan(time) && !(time >= 0.0 && time <= 1e9)) fail("time_s", "seconds since the start of the measurement, from 0 to 1e9");
        if (!runs[{run, direction}].emplace(position, RunReading{value, time, temperature, n}).second)
          fail("row", fmt::format("run {} {} at position {} is given twice", run, direction > 0 ? "forward" : "backward", fields[0]));
      });
  n = 0;
  if (!componentGiven) fail("component", "missing '# component:' (e.g. '# component: xrx')");
  if (runs.empty()) fail("row", "no readings");
  // Every run in both directions at the positions of the first run's forward pass.
  const auto& first = runs.begin()->second;
  std::set<int> runNumbers;
  for (const auto& [key, readings] : runs) runNumbers.insert(key.first);
  for (const int run : runNumbers)
    for (const int direction : {1, -1}) {
      const auto it = runs.find({run, direction});
      const std::string what = fmt::format("run {} {}", run, direction > 0 ? "forward" : "backward");
      if (it == runs.end()) {
        n = runs.at({run, -direction}).begin()->second.line;  // the run's other pass
        fail("direction", what + " is missing: every run goes both ways");
      }
      n = std::min_element(it->second.begin(), it->second.end(), [](const auto& a, const auto& b) {
            return a.second.line < b.second.line;
          })->second.line;
      if (it->second.size() != first.size())
        fail("position", fmt::format("{} has {} positions, run {} forward {} (ragged runs)", what, it->second.size(),
                                     runs.begin()->first.first, first.size()));
      auto b = first.begin();
      for (auto a = it->second.begin(); a != it->second.end(); ++a, ++b)
        if (std::abs(a->first - b->first) > 1e-9 * std::max(1.0, std::abs(b->first))) {
          n = a->second.line;
          fail("position", what + " is at a position the other runs do not have (ragged runs)");
        }
    }
  if (runNumbers.size() < 2) fail("run", "one run: the seed's procedure averages several (20); give at least 2");
  n = 0;
  const auto m = static_cast<Eigen::Index>(first.size());
  const auto runCount = static_cast<Eigen::Index>(runNumbers.size());
  for (const auto& [pos, r] : first) f.runs.positions.push_back(pos);
  const bool timed = std::find(header.begin(), header.end(), "time_s") != header.end();
  const bool heated = std::find(header.begin(), header.end(), "temperature_C") != header.end();
  if (f.expansion && !heated) fail("expansion", "an expansion coefficient needs the temperature_C column");
  auto fill = [&](int direction, Eigen::MatrixXd& values, Eigen::MatrixXd& times, Eigen::MatrixXd& temperatures) {
    values.resize(m, runCount);
    if (timed) times.resize(m, runCount);
    if (heated) temperatures.resize(m, runCount);
    Eigen::Index j = 0;
    for (const int run : runNumbers) {
      Eigen::Index i = 0;
      for (const auto& [pos, r] : runs.at({run, direction})) {
        values(i, j) = r.value;
        if (timed) times(i, j) = r.time;
        if (heated) temperatures(i, j) = r.temperature;
        ++i;
      }
      ++j;
    }
  };
  fill(1, f.runs.forward, f.runs.forwardTime, f.forwardTemperature);
  fill(-1, f.runs.backward, f.runs.backwardTime, f.backwardTemperature);
  if (f.runs.positions.size() < 2) fail("position", "a run needs two or more positions");
  return f;
}

std::string componentRunsCsv(const Machine& machine, const ComponentRunsFile& f) {
  const bool angle = f.component.component >= 3;
  const Axis& axis = machine.axes[static_cast<size_t>(f.component.axis)];
  const double unit = angle ? kArcsec : kMicro, pos = axis.isRotary() ? kDeg : 1.0;
  std::string out = fmt::format("# component: {}\n# unit: {}\n", f.componentName, angle ? "arcsec" : "um");
  if (!f.instrument.empty()) out += "# instrument: " + f.instrument + "\n";
  if (f.uncertainty) out += fmt::format("# uncertainty: {:.6g} {}\n", *f.uncertainty / unit, angle ? "arcsec" : "um");
  if (f.abbeOffset) out += fmt::format("# abbe_offset: {:g}, {:g}, {:g} mm\n", f.abbeOffset->x(), f.abbeOffset->y(), f.abbeOffset->z());
  const bool timed = f.runs.forwardTime.size() > 0;
  out += timed ? "position,run,direction,value,time_s\n" : "position,run,direction,value\n";
  for (Eigen::Index j = 0; j < f.runs.forward.cols(); ++j)
    for (const int direction : {1, -1}) {
      const auto& values = direction > 0 ? f.runs.forward : f.runs.backward;
      const auto& times = direction > 0 ? f.runs.forwardTime : f.runs.backwardTime;
      for (Eigen::Index k = 0; k < values.rows(); ++k) {
        const Eigen::Index i = direction > 0 ? k : values.rows() - 1 - k;
        out += fmt::format("{:.10g},{},{},{:.6f}", f.runs.positions[static_cast<size_t>(i)] / pos, j + 1, direction, values(i, j) / unit);
        out += timed ? fmt::format(",{:.3f}\n", times(i, j)) : "\n";
      }
    }
  return out;
}

ComponentRunsFile readComponentRuns(const Machine& machine, const std::string& path) {
  return parseComponentRuns(machine, readTextFile(path), path);
}

}  // namespace mtacc
