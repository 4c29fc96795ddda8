#include "mtacc/io/measurement_csv.hpp"

#include "mtacc/core/text_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/measurement/standard_paths.hpp"

namespace mtacc {
namespace {

struct Meta {
  std::string value;
  int line = 0;
};

// The '# key: value' lines a measurement file may have; `note` is free text.
constexpr std::array<const char*, 14> kMetaKeys{"machine", "instrument", "name",      "length", "target",
                                                "set_at",  "plane",      "pose",      "tool_ball", "direction",
                                                "feed",    "noise",      "estimate",  "note"};

bool isMetaKey(const std::string& key) {
  return std::find(kMetaKeys.begin(), kMetaKeys.end(), key) != kMetaKeys.end();
}

// '# key: value' lines before the header row; other comment lines have no colon.
std::map<std::string, Meta> readMeta(const std::string& text, const std::string& source) {
  std::map<std::string, Meta> meta;
  std::stringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] != '#') break;
    const auto assignment = commentAssignment(s);
    if (!assignment) {
      const std::string comment = trim(s.substr(1));
      const std::string firstWord = comment.substr(0, comment.find(' '));
      if (isMetaKey(firstWord))
        throw InputError(InputLocation{source, n, firstWord}, "write '# " + firstWord + ": value' (the colon is missing)");
      continue;
    }
    const auto& [key, value] = *assignment;
    if (!isMetaKey(key))
      throw InputError(InputLocation{source, n, key},
                       "unknown key (expected one of: machine, instrument, name, length, target, set_at, plane, pose, "
                       "tool_ball, direction, feed, noise, estimate, note)");
    if (!meta.emplace(key, Meta{value, n}).second)
      throw InputError(InputLocation{source, n, key}, "given twice (first on line " + std::to_string(meta[key].line) + ")");
  }
  return meta;
}

class MetaReader {
 public:
  MetaReader(std::string file, std::map<std::string, Meta> meta) : file_(std::move(file)), meta_(std::move(meta)) {}
  bool has(const std::string& key) const { return meta_.count(key) > 0; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(InputLocation{file_, has(key) ? meta_.at(key).line : 1, key}, what);
  }
  const std::string& text(const std::string& key) const {
    if (!has(key)) fail(key, "missing '# " + key + ": ...' line");
    return meta_.at(key).value;
  }
  double quantity(const std::string& key, Dimension d) const { return parse(key, text(key), d); }
  // "x, y, z mm"
  Vec3 lengths(const std::string& key) const {
    try {
      return parseLengths(text(key), key);
    } catch (const InputError& e) {
      fail(key, e.reason());
    }
  }
  // "1000 mm/min"
  double feed(const std::string& key) const {
    std::string value = text(key);
    const auto slash = value.rfind("/min");
    if (slash == std::string::npos || slash + 4 != value.size()) fail(key, "expected a feed in mm/min");
    const double f = parse(key, value.substr(0, slash), Dimension::Length);
    if (!(f > 0)) fail(key, "the feed must be positive");
    return f;
  }
  Vec3 numbers(const std::string& value, const std::string& key) const {
    auto parts = splitFields(value);
    if (parts.size() != 3) fail(key, "expected three numbers 'x, y, z'");
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      try {
        size_t used = 0;
        v[k] = std::stod(parts[static_cast<size_t>(k)], &used);
        if (used != parts[static_cast<size_t>(k)].size() || !std::isfinite(v[k])) throw InvalidInput("");
      } catch (const std::exception&) {
        fail(key, "not a number: '" + parts[static_cast<size_t>(k)] + "'");
      }
    }
    return v;
  }
  Vec3 unitVector(const std::string& key) const {
    const Vec3 v = numbers(text(key), key);
    if (v.norm() < 1e-12) fail(key, "a direction cannot be zero");
    return v.normalized();
  }
  // "X=300 mm, Y=200 mm, B=0 deg": every commanded axis.
  std::vector<double> pose(const Machine& m, const std::string& key) const {
    std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
    std::vector<bool> seen(q.size(), false);
    for (const auto& part : splitFields(text(key))) {
      const auto eq = part.find('=');
      const int j = eq == std::string::npos ? -1 : m.commandedAxisIndex(trim(part.substr(0, eq)));
      if (j < 0) fail(key, "expected 'AXIS=value unit' for each axis, found '" + part + "'");
      const bool rotary = m.axes[static_cast<size_t>(j)].isRotary();
      q[static_cast<size_t>(j)] = parse(key, part.substr(eq + 1), rotary ? Dimension::Angle : Dimension::Length);
      seen[static_cast<size_t>(j)] = true;
    }
    for (size_t j = 0; j < q.size(); ++j)
      if (!seen[j]) fail(key, "axis " + m.axes[j].name + " is missing");
    return q;
  }

 private:
  double parse(const std::string& key, const std::string& value, Dimension d) const {
    std::string reason;
    const auto q = parseQuantity(value, &reason);
    if (!q) fail(key, reason);
    if (q->dimension != d) fail(key, std::string("expected ") + withArticle(d));
    return q->value;
  }
  std::string file_;
  std::map<std::string, Meta> meta_;
};

std::vector<std::string> readingColumns(Instrument i) {
  switch (i) {
    case Instrument::Ballbar: return {"dL_um"};
    case Instrument::RTest:
    case Instrument::TouchProbe: return {"dx_um", "dy_um", "dz_um"};
    case Instrument::Directional: return {"d_um"};
  }
  return {};
}

int column(const CsvTable& t, const std::string& name) {
  for (size_t c = 0; c < t.header.size(); ++c)
    if (t.header[c] == name) return static_cast<int>(c);
  return -1;
}

std::string poseText(const Machine& m, const std::vector<double>& q) {
  std::string out;
  for (int j = 0; j < m.commandedCount(); ++j) {
    const auto& a = m.axes[static_cast<size_t>(j)];
    out += fmt::format("{}{}={:.9g} {}", j ? ", " : "", a.name, a.isRotary() ? q[static_cast<size_t>(j)] / kDeg : q[static_cast<size_t>(j)],
                       a.isRotary() ? "deg" : "mm");
  }
  return out;
}

std::string vectorText(const Vec3& v, const char* unit) {
  return fmt::format("{:.9g}, {:.9g}, {:.9g}{}{}", v.x(), v.y(), v.z(), *unit ? " " : "", unit);
}

}  // namespace

MeasurementRun parseMeasurementCsv(const KinematicModel& nominal, const std::string& text, const std::string& source) {
  const Machine& m = *nominal.machine;
  const MetaReader meta(source, readMeta(text, source));
  if (meta.has("machine") && meta.text("machine") != m.name)
    meta.fail("machine", "the file was measured on '" + meta.text("machine") + "', not on '" + m.name + "'");
  MeasurementRun run;
  const auto instrument = parseInstrument(meta.text("instrument"));
  if (!instrument) meta.fail("instrument", "expected ballbar, rtest, probe or directional");
  run.instrument = *instrument;
  run.name = meta.has("name") ? meta.text("name") : source.substr(source.find_last_of('/') + 1);
  if (meta.has("tool_ball")) run.setup.toolBall = meta.lengths("tool_ball");
  if (meta.has("feed")) run.feed = meta.feed("feed");
  if (meta.has("noise")) {
    run.noise = meta.quantity("noise", Dimension::Length);
    if (!(*run.noise >= 1e-6 && *run.noise <= 1.0)) meta.fail("noise", "the reading noise must be from 1 nm to 1 mm");
  }
  if (meta.has("estimate"))
    for (const auto& name : splitFields(meta.text("estimate"))) {
      const auto p = parseSetupParameter(name);
      if (!p || !appliesTo(*p, run.instrument))
        meta.fail("estimate", "'" + name + "' is not a set-up parameter of a " + instrumentName(run.instrument) +
                                  " (xT yT zT xW yW zW" +
                                  (run.instrument == Instrument::RTest ? " aN bN cN" : "") +
                                  (run.instrument == Instrument::Ballbar ? " dL" : "") + ")");
      run.estimate.push_back(*p);
    }
  switch (run.instrument) {
    case Instrument::Ballbar:
      run.setup.length = meta.quantity("length", Dimension::Length);
      if (!(run.setup.length > 0)) meta.fail("length", "the bar length must be positive");
      if (meta.has("set_at")) run.setup.setAt = meta.pose(m, "set_at");
      if (meta.has("target") || !run.setup.setAt) run.setup.target = meta.lengths("target");
      if (!run.setup.setAt) {
        // The centre ball is set where the tool ball is with the centre commanded.
        auto q = meta.has("pose") ? meta.pose(m, "pose") : std::vector<double>(static_cast<size_t>(m.commandedCount()), 0.0);
        try {
          placeToolPoint(nominal, q, run.setup.toolBall, run.setup.target);
        } catch (const UnreachablePose& e) {
          meta.fail("target", e.what());
        }
        run.setup.setAt = q;
      }
      if (meta.has("plane")) {
        try {
          run.plotAxes = planeAxes(meta.text("plane"));
        } catch (const InvalidInput& e) {
          meta.fail("plane", e.what());
        }
      }
      break;
    case Instrument::RTest:
    case Instrument::TouchProbe: run.setup.target = meta.lengths("target"); break;
    case Instrument::Directional: run.setup.direction = meta.unitVector("direction"); break;
  }

  const CsvTable table = parseCsv(text, source);
  std::vector<std::string> other = readingColumns(run.instrument);
  const auto readingCols = requireColumns(table, other);
  if (run.instrument == Instrument::Ballbar) other.insert(other.end(), {"angle_deg", "sense"});
  const int angleCol = column(table, "angle_deg"), senseCol = column(table, "sense");
  const auto n = static_cast<Eigen::Index>(table.rows.size());
  const bool axisColumns = column(table, m.axes[0].name) >= 0;
  if (run.instrument == Instrument::Ballbar) {
    if (angleCol >= 0)
      for (size_t i = 0; i < table.rows.size(); ++i) {
        const double deg = table.rows[i][static_cast<size_t>(angleCol)];
        if (!(std::abs(deg * kDeg) <= kLargestAngle))
          throw InputError(InputLocation{source, table.lines[i], "angle_deg"}, "out of range: an angle lies within ±36000 deg");
        run.angle.push_back(deg * kDeg);
      }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double s = senseCol >= 0 ? table.rows[static_cast<size_t>(i)][static_cast<size_t>(senseCol)] : 1.0;
      if (s != 1.0 && s != -1.0)
        throw InputError(InputLocation{source, table.lines[static_cast<size_t>(i)], "sense"}, "sense must be 1 or -1");
      run.sense.push_back(static_cast<int>(s));
    }
  }
  if (axisColumns) {
    auto poses = posesFromCsv(m, table, other);
    run.q = std::move(poses.q);
    run.direction = std::move(poses.direction);
  } else {
    // A ballbar export: angle and dL only, the circle named in the header.
    if (run.instrument != Instrument::Ballbar || angleCol < 0 || !meta.has("plane"))
      throw InputError(InputLocation{source, table.headerLine, m.axes[0].name},
                       "missing axis columns (only a ballbar file with angle_deg and '# plane:' may omit them)");
    const auto base = meta.has("pose") ? meta.pose(m, "pose") : std::vector<double>(static_cast<size_t>(m.commandedCount()), 0.0);
    const Mat3 toMachine = workpiecePose(nominal, base.data(), nullptr).linear();
    run.q.resize(n, m.commandedCount());
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = run.angle[static_cast<size_t>(i)];
      auto q = base;
      placeToolPoint(nominal, q, run.setup.toolBall,
                     run.setup.target + toMachine.transpose() * (run.setup.length * (std::cos(t) * run.plotAxes[0] +
                                                                                      std::sin(t) * run.plotAxes[1])));
      if (const auto violation = m.travelViolation(q); !violation.empty())
        throw InputError(InputLocation{source, table.lines[static_cast<size_t>(i)], "angle_deg"},
                         "the circle's pose " + violation);
      for (size_t j = 0; j < q.size(); ++j) run.q(i, static_cast<Eigen::Index>(j)) = q[j];
    }
  }
  const int k = readingSize(run.instrument);
  run.readings.resize(n, k);
  constexpr double kLargestReading = 1e6;  // um: a deviation of 1 m is no reading
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < k; ++c) {
      const auto col = static_cast<size_t>(readingCols[static_cast<size_t>(c)]);
      const double um = table.rows[static_cast<size_t>(i)][col];
      if (!(std::abs(um) <= kLargestReading))
        throw InputError(InputLocation{source, table.lines[static_cast<size_t>(i)], table.header[col]},
                         fmt::format("{:g} um is out of range: a reading lies within ±1e6 um", um));
      run.readings(i, c) = um * 1e-3;
    }
  return run;
}

MeasurementRun readMeasurementCsv(const KinematicModel& nominal, const std::string& path) {
  return parseMeasurementCsv(nominal, readTextFile(path), path);
}

std::string measurementCsv(const Machine& m, const MeasurementRun& run) {
  if (run.readings.rows() != run.poses()) throw InvalidInput("run '" + run.name + "' has no readings");
  std::string out = "# mtacc measurement (docs/file-formats.md)\n";
  out += "# machine: " + m.name + "\n";
  out += "# instrument: " + instrumentName(run.instrument) + "\n# name: " + run.name + "\n";
  out += "# tool_ball: " + vectorText(run.setup.toolBall, "mm") + "\n";
  out += fmt::format("# feed: {:.9g} mm/min\n", run.feed);
  if (run.noise) out += fmt::format("# noise: {:.9g} um\n", *run.noise * 1e3);
  if (!run.estimate.empty()) {
    out += "# estimate: ";
    for (size_t i = 0; i < run.estimate.size(); ++i) out += (i ? ", " : "") + setupParameterName(run.estimate[i]);
    out += "\n";
  }
  switch (run.instrument) {
    case Instrument::Ballbar:
      out += fmt::format("# length: {:.9g} mm\n", run.setup.length);
      out += "# target: " + vectorText(run.setup.target, "mm") + "\n";
      if (run.setup.setAt) out += "# set_at: " + poseText(m, *run.setup.setAt) + "\n";
      for (const char* plane : {"XY", "YZ", "ZX"})
        if (planeAxes(plane)[0].isApprox(run.plotAxes[0]) && planeAxes(plane)[1].isApprox(run.plotAxes[1]))
          out += std::string("# plane: ") + plane + "\n";
      break;
    case Instrument::RTest:
    case Instrument::TouchProbe: out += "# target: " + vectorText(run.setup.target, "mm") + "\n"; break;
    case Instrument::Directional: out += "# direction: " + vectorText(run.setup.direction, "") + "\n"; break;
  }
  std::string header;
  for (int j = 0; j < m.commandedCount(); ++j) header += (j ? "," : "") + m.axes[static_cast<size_t>(j)].name;
  if (run.direction.size())
    for (int j = 0; j < m.commandedCount(); ++j) header += "," + m.axes[static_cast<size_t>(j)].name + "_dir";
  const bool angles = run.instrument == Instrument::Ballbar && run.angle.size() == static_cast<size_t>(run.poses());
  if (angles) header += ",angle_deg,sense";
  for (const auto& c : readingColumns(run.instrument)) header += "," + c;
  out += header + "\n";
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    std::string row;
    for (int j = 0; j < m.commandedCount(); ++j) {
      const double v = run.q(i, j);
      row += fmt::format("{}{:.9f}", j ? "," : "", m.axes[static_cast<size_t>(j)].isRotary() ? v / kDeg : v);
    }
    if (run.direction.size())
      for (int j = 0; j < m.commandedCount(); ++j) row += fmt::format(",{}", run.direction(i, j));
    if (angles)
      row += fmt::format(",{:.9f},{}", run.angle[static_cast<size_t>(i)] / kDeg,
                         run.sense.size() > static_cast<size_t>(i) ? run.sense[static_cast<size_t>(i)] : 1);
    for (Eigen::Index c = 0; c < run.readings.cols(); ++c) row += fmt::format(",{:.6f}", run.readings(i, c) * 1e3);
    out += row + "\n";
  }
  return out;
}

}  // namespace mtacc
