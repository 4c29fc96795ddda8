#include "mtacc/io/drift_test_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr const char* kProbeColumns[] = {"x1_um", "y1_um", "x2_um", "y2_um", "z_um"};
constexpr double kLargestProbeReading = 10.0;  // mm
constexpr double kFastestSpindle = 2e5;        // rpm

constexpr double kLargestPosition = 1e5;       // mm

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// An axis position column: one capital letter and "_mm", e.g. Z_mm.
bool isAxisColumn(const std::string& name) { return name.size() == 4 && name[0] >= 'A' && name[0] <= 'Z' && endsWith(name, "_mm"); }

}  // namespace

DriftTestFile parseDriftTestCsv(const std::string& text, const std::string& source) {
  DriftTestFile out;
  out.file = source;
  int n = 0;
  std::optional<std::pair<double, double>> probeZ;
  int probeZLine = 0;
  std::map<std::string, std::pair<std::string, int>> locations;
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        const auto fail = [&](const std::string& what) { throw InputError({source, n, key}, what); };
        if (key == "probe_z") {
          if (probeZ) fail(fmt::format("given twice (first on line {})", probeZLine));
          try {
            const auto z = parseLengthList(value, 2, key, "'z1, z2 mm' (machine z of probe sets 1 and 2)", "50, 150 mm");
            probeZ = {z[0], z[1]};
          } catch (const InputError& e) {
            fail(e.reason());
          }
          if (!(std::fabs(probeZ->first) < 1e5 && std::fabs(probeZ->second) < 1e5)) fail("probe heights within +-100 m");
          probeZLine = n;
        } else if (key == "sensor") {
          const auto comma = value.find(',');
          const std::string name = trim(value.substr(0, comma)), where = comma == std::string::npos ? "" : trim(value.substr(comma + 1));
          if (name.empty()) fail("expected 'NAME, where it sits'");
          if (!locations.emplace(name, std::pair{where, n}).second) fail(fmt::format("sensor '{}' given twice", name));
        } else if (key != "note") {
          fail("unknown key (expected probe_z, sensor, note)");
        }
      },
      [](const std::string&) {});

  const auto table = parseCsv(text, source);
  out.headerLine = table.headerLine;
  const auto column = [&](const std::string& name) {
    const auto it = std::find(table.header.begin(), table.header.end(), name);
    return it == table.header.end() ? -1 : static_cast<int>(it - table.header.begin());
  };
  const auto headerError = [&](const std::string& key, const std::string& what) { throw InputError({source, table.headerLine, key}, what); };
  if (column("time_s") < 0) headerError("time_s", "missing column 'time_s'");
  bool anyProbe = false;
  for (const auto& name : table.header) {
    const bool probe = std::find(std::begin(kProbeColumns), std::end(kProbeColumns), name) != std::end(kProbeColumns);
    anyProbe = anyProbe || probe;
    if (probe || name == "time_s" || name == "spindle_rpm") continue;
    if (isAxisColumn(name)) {
      out.axes.push_back(name.substr(0, 1));
    } else if (endsWith(name, "_C")) {
      out.sensors.push_back(name.substr(0, name.size() - 2));
    } else {
      headerError(name, "unknown column (expected time_s, x1_um, y1_um, x2_um, y2_um, z_um, spindle_rpm, axis positions such as Z_mm "
                        "and temperatures NAME_C)");
    }
  }
  if (!anyProbe) headerError("x1_um", "no probe column (x1_um, y1_um, x2_um, y2_um, z_um)");
  const long samples = static_cast<long>(table.rows.size());
  if (samples < 3) throw InputError({source, table.lines.back(), "time_s"}, fmt::format("{} samples, at least 3 needed", samples));

  const auto values = [&](int c, double scale, double low, double high, const std::string& range) {
    Eigen::VectorXd v(samples);
    for (long k = 0; k < samples; ++k) {
      v[k] = table.rows[static_cast<size_t>(k)][static_cast<size_t>(c)] * scale;
      if (!(v[k] >= low && v[k] <= high))
        throw InputError({source, table.lines[static_cast<size_t>(k)], table.header[static_cast<size_t>(c)]}, range);
    }
    return v;
  };
  out.time = values(column("time_s"), 1.0, -1e9, 1e9, "time within +-1e9 s");
  for (long k = 1; k < samples; ++k)
    if (!(out.time[k] > out.time[k - 1]))
      throw InputError({source, table.lines[static_cast<size_t>(k)], "time_s"},
                       fmt::format("time does not increase ({} s after {} s)", out.time[k], out.time[k - 1]));
  Eigen::VectorXd* probes[] = {&out.probes.x1, &out.probes.y1, &out.probes.x2, &out.probes.y2, &out.probes.z};
  for (size_t p = 0; p < 5; ++p)
    if (const int c = column(kProbeColumns[p]); c >= 0)
      *probes[p] = values(c, kMicro, -kLargestProbeReading, kLargestProbeReading, "a probe reading beyond +-10 mm (10000 um)");
  if (const int c = column("spindle_rpm"); c >= 0) out.spindleSpeed = values(c, 1.0, 0.0, kFastestSpindle, "a spindle speed from 0 to 200000 rpm");
  out.positions.resize(samples, static_cast<long>(out.axes.size()));
  for (size_t a = 0; a < out.axes.size(); ++a)
    out.positions.col(static_cast<long>(a)) = values(column(out.axes[a] + "_mm"), 1.0, -kLargestPosition, kLargestPosition, "an axis position beyond +-100 m");
  out.temperatures.resize(samples, static_cast<long>(out.sensors.size()));
  for (size_t s = 0; s < out.sensors.size(); ++s) {
    out.temperatures.col(static_cast<long>(s)) = values(column(out.sensors[s] + "_C"), 1.0, -50.0, 150.0, "a temperature outside -50 .. 150 degC");
    const auto it = locations.find(out.sensors[s]);
    out.sensorLocations.push_back(it == locations.end() ? "" : it->second.first);
  }
  for (const auto& [name, where] : locations)
    if (std::find(out.sensors.begin(), out.sensors.end(), name) == out.sensors.end())
      throw InputError({source, where.second, "sensor"}, fmt::format("no column '{}_C' for sensor '{}'", name, name));

  const bool tilts = (out.probes.x1.size() && out.probes.x2.size()) || (out.probes.y1.size() && out.probes.y2.size());
  if (tilts && !probeZ) headerError("probe_z", "two probe sets need '# probe_z: z1, z2 mm' for the tilts");
  if (probeZ) {
    if (tilts && !(std::fabs(probeZ->second - probeZ->first) > 1e-6))
      throw InputError({source, probeZLine, "probe_z"}, "the two probe sets at one height: no tilt");
    out.probes.z1 = probeZ->first;
    out.probes.z2 = probeZ->second;
  }
  if ((out.probes.x2.size() && !out.probes.x1.size()) || (out.probes.y2.size() && !out.probes.y1.size()))
    headerError(out.probes.x2.size() && !out.probes.x1.size() ? "x2_um" : "y2_um", "a probe of set 2 without its set-1 probe");
  return out;
}

std::string driftTestCsv(const DriftTestFile& test, const std::string& note) {
  std::string out = fmt::format("# note: {}\n", note);
  const Eigen::VectorXd* probes[] = {&test.probes.x1, &test.probes.y1, &test.probes.x2, &test.probes.y2, &test.probes.z};
  if (test.probes.z1 != test.probes.z2) out += fmt::format("# probe_z: {:g}, {:g} mm\n", test.probes.z1, test.probes.z2);
  for (size_t s = 0; s < test.sensors.size(); ++s)
    if (!test.sensorLocations[s].empty()) out += fmt::format("# sensor: {}, {}\n", test.sensors[s], test.sensorLocations[s]);
  out += "time_s";
  for (size_t p = 0; p < 5; ++p)
    if (probes[p]->size()) out += fmt::format(",{}", kProbeColumns[p]);
  if (test.spindleSpeed) out += ",spindle_rpm";
  for (const auto& a : test.axes) out += "," + a + "_mm";
  for (const auto& s : test.sensors) out += "," + s + "_C";
  out += '\n';
  for (long k = 0; k < test.time.size(); ++k) {
    out += fmt::format("{:g}", test.time[k]);
    for (const auto* probe : probes)
      if (probe->size()) out += fmt::format(",{:.3f}", (*probe)[k] / kMicro);
    if (test.spindleSpeed) out += fmt::format(",{:g}", (*test.spindleSpeed)[k]);
    for (long a = 0; a < test.positions.cols(); ++a) out += fmt::format(",{:.4f}", test.positions(k, a));
    for (long s = 0; s < test.temperatures.cols(); ++s) out += fmt::format(",{:.3f}", test.temperatures(k, s));
    out += '\n';
  }
  return out;
}

DriftTestFile readDriftTestCsv(const std::string& path) { return parseDriftTestCsv(readTextFile(path), path); }

}  // namespace mtacc
