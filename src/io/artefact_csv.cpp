#include "mtacc/io/artefact_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "measured_point_limits.hpp"

namespace mtacc {
namespace {

constexpr int kMostFeatures = 10000;
constexpr double kOffDeclared = 1.0;   // mm a feature may lie off the declared line or plane
constexpr double kMeasuredOff = 10.0;  // mm a measured feature may lie from its placed certificate

const char* const kColumns[] = {"feature", "u", "v", "w", "U", "x", "y", "z"};

struct Row {
  int line;
  Vec3 calibrated;
  std::optional<double> expanded;  // U (k = 2), mm
  std::optional<Vec3> measured;
};

ProbedDirections parseProbed(const std::string& value) {
  if (value == "all") return ProbedDirections::All;
  if (value == "in-plane") return ProbedDirections::InPlane;
  if (value == "along") return ProbedDirections::Along;
  throw InputError(InputLocation{"", 0, "probed"}, "expected all, in-plane or along");
}

const char* probedName(ProbedDirections p) {
  return p == ProbedDirections::All ? "all" : p == ProbedDirections::InPlane ? "in-plane" : "along";
}

}  // namespace

ArtefactMeasurement parseArtefactMeasurement(const Machine& machine, const std::string& text, const std::string& source) {
  ArtefactMeasurement m;
  m.file = source;
  m.placement.name = std::filesystem::path(source).stem().string();
  int n = 0;
  const auto fail = [&](const std::string& key, const std::string& what) { throw InputError(InputLocation{source, n, key}, what); };
  std::map<std::string, int> seen;
  ProbingHeader header;
  bool named = false, dimensionGiven = false, headerSeen = false;
  int alignmentLine = 0;
  std::vector<std::string> alignmentIds;
  std::optional<double> certificate;
  std::map<std::string, int> index;
  std::vector<Row> rows;
  readCommentedLines(
      text, n,
      [&](const std::string& key, const std::string& value) {
        if (key != "note" && !seen.emplace(key, n).second) fail(key, fmt::format("given twice (first on line {})", seen[key]));
        try {
          if (key == "artefact") {
            if (value.empty()) fail(key, "give the artefact a name");
            m.artefact.name = value;
            named = true;
            m.artefactLine = n;
          } else if (key == "dimension") {
            m.artefact.dimension = parseCount(value, key, 1, 3);
            dimensionGiven = true;
          } else if (key == "probed") {
            m.placement.probed = parseProbed(value);
          } else if (key == "alignment") {
            alignmentLine = n;
            const auto space = value.find(' ');
            const std::string method = value.substr(0, space);
            if (method == "least-squares" || method == "least-squares-scaled") {
              if (space != std::string::npos) fail(key, "a least-squares alignment takes no features");
              m.alignment.method = method == "least-squares" ? AlignmentMethod::LeastSquares : AlignmentMethod::LeastSquaresScaled;
            } else if (method == "three-point") {
              m.alignment.method = AlignmentMethod::ThreePoint;
              if (space != std::string::npos) alignmentIds = splitFields(value.substr(space + 1));
              if (alignmentIds.size() > 3) fail(key, "at most three features: origin, direction, plane");
            } else {
              fail(key, "expected least-squares, least-squares-scaled or three-point [A, B, C]");
            }
          } else if (key == "certificate") {
            certificate = parseQuantityAs(value, Dimension::Length, key);
            if (!(*certificate >= 0.0 && *certificate < 1.0)) fail(key, "an expanded uncertainty (k = 2) from 0 to 1 mm");
          } else if (key != "note" && !readProbingKey(machine, key, value, n, header)) {
            fail(key,
                 "unknown key (expected artefact, dimension, origin, axes, probed, alignment, certificate, stylus, pose, temperatures, "
                 "expansion, probe, simulation, note)");
          }
        } catch (const InputError& e) {
          if (!e.where().file.empty()) throw;
          fail(key, e.reason());
        }
      },
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (!headerSeen) {
          if (fields != std::vector<std::string>(std::begin(kColumns), std::end(kColumns)))
            fail("header", "expected the header 'feature,u,v,w,U,x,y,z'");
          headerSeen = true;
          return;
        }
        if (fields.size() != 8) fail("row", fmt::format("expected 8 fields, found {}", fields.size()));
        if (fields[0].empty()) fail("feature", "a feature needs a name");
        if (const auto [it, fresh] = index.emplace(fields[0], static_cast<int>(rows.size())); !fresh)
          fail("feature", fmt::format("feature {} is given twice (first on line {})", fields[0], rows[static_cast<size_t>(it->second)].line));
        if (rows.size() >= kMostFeatures) fail("feature", fmt::format("at most {} features", kMostFeatures));
        Row r{n, Vec3::Zero(), std::nullopt, std::nullopt};
        const auto coordinate = [&](size_t f) {
          const double x = parseNumber(fields[f], kColumns[f]);
          if (!(std::abs(x) <= kLargestMeasuredCoordinate)) fail(kColumns[f], fmt::format("within +-{} mm", kLargestMeasuredCoordinate));
          return x;
        };
        try {
          r.calibrated = {coordinate(1), coordinate(2), coordinate(3)};
          if (!fields[4].empty()) {
            r.expanded = parseNumber(fields[4], "U") * 1e-3;
            if (!(*r.expanded >= 0.0 && *r.expanded < 1.0)) fail("U", "an expanded uncertainty (k = 2) from 0 to 1000 um");
          }
          const int given = !fields[5].empty() + !fields[6].empty() + !fields[7].empty();
          if (given == 3) r.measured = Vec3(coordinate(5), coordinate(6), coordinate(7));
          else if (given > 0) fail(fields[5].empty() ? "x" : fields[6].empty() ? "y" : "z", "give all three measured coordinates or none");
        } catch (const InputError& e) {
          if (!e.where().file.empty()) throw;
          fail(e.where().key, e.reason());
        }
        rows.push_back(r);
      });
  n = 0;
  if (!named) fail("artefact", "missing '# artefact: NAME'");
  if (!dimensionGiven) fail("dimension", "missing '# dimension: 1, 2 or 3' (features along u, in the u-v plane, or anywhere)");
  if (!header.originGiven) fail("origin", "missing '# origin: x, y, z mm' (the artefact frame's origin in the workpiece frame)");
  if (!headerSeen) fail("header", "no header row 'feature,u,v,w,U,x,y,z'");
  const int least = m.artefact.dimension == 1 ? 2 : 3;
  if (static_cast<int>(rows.size()) < least) fail("feature", fmt::format("a {}-D artefact needs at least {} features", m.artefact.dimension, least));
  const auto at = [&](const char* key) { n = seen.count(key) ? seen[key] : 0; };
  at("probed");
  if (m.placement.probed == ProbedDirections::Along && m.artefact.dimension != 1)
    fail("probed", "'along' reads one direction: only for a 1-D artefact (dimension: 1)");
  if (m.placement.probed == ProbedDirections::InPlane && m.artefact.dimension == 3)
    fail("probed", "'in-plane' reads u and v: not for a 3-D artefact");
  at("probe");
  if (!header.probe.empty() && static_cast<int>(header.probe.size()) != directionCount(m.placement.probed))
    fail("probe", fmt::format("give one 2S per probed direction ({})", directionCount(m.placement.probed)));
  n = 0;
  m.placement.origin = header.origin;
  m.originLine = header.originLine;
  m.placement.u = header.u;
  m.placement.v = header.v;
  m.placement.stylus = header.stylus;
  m.placement.fixedAxes = header.pose.empty() ? machine.referencePose : header.pose;
  m.temperatures = header.temperatures;
  m.probe = header.probe;
  m.simulation = header.simulation;
  const bool layout = !rows.front().measured;
  m.certificateStated = true;
  for (const auto& [id, k] : index) {
    const Row& r = rows[static_cast<size_t>(k)];
    n = r.line;
    if (m.artefact.dimension == 1 && !(std::hypot(r.calibrated.y(), r.calibrated.z()) <= kOffDeclared))
      fail("v", fmt::format("feature {} lies {:.3g} mm off the artefact's u axis (dimension: 1)", id, std::hypot(r.calibrated.y(), r.calibrated.z())));
    if (m.artefact.dimension == 2 && !(std::abs(r.calibrated.z()) <= kOffDeclared))
      fail("w", fmt::format("feature {} lies {:.3g} mm off the artefact's u-v plane (dimension: 2); declare dimension: 3", id, r.calibrated.z()));
    if (r.measured.has_value() == layout)
      fail("x", layout ? fmt::format("feature {} is measured but the first feature is not (a layout has no measured values)", id)
                       : fmt::format("feature {} has a certificate position but no measured value", id));
    if (r.measured && !((*r.measured - m.placement.place(r.calibrated)).norm() <= kMeasuredOff))
      fail("x", fmt::format("feature {} measured {:.3g} mm from its place by the certificate and the origin (more than {} mm)", id,
                            (*r.measured - m.placement.place(r.calibrated)).norm(), kMeasuredOff));
  }
  n = 0;
  m.measured.resize(layout ? 0 : static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k) {
    const auto& r = rows[k];
    const double expanded = r.expanded ? *r.expanded : certificate.value_or(0.0);
    m.certificateStated = m.certificateStated && (r.expanded || certificate);
    m.artefact.features.push_back({"", r.calibrated, 0.5 * expanded});
    m.featureLines.push_back(r.line);
    if (!layout) m.measured.row(static_cast<Eigen::Index>(k)) = r.measured->transpose();
  }
  for (const auto& [id, k] : index) m.artefact.features[static_cast<size_t>(k)].id = id;
  m.alignmentLine = alignmentLine;
  for (size_t k = 0; k < alignmentIds.size(); ++k) {
    const auto it = index.find(alignmentIds[k]);
    if (it == index.end()) {
      n = alignmentLine;
      fail("alignment", fmt::format("feature {} is not in the table", alignmentIds[k]));
    }
    m.alignment.features[k] = it->second;
  }
  return m;
}

ArtefactMeasurement readArtefactMeasurement(const Machine& machine, const std::string& path) {
  return parseArtefactMeasurement(machine, readTextFile(path), path);
}

std::string artefactMeasurementCsv(const Machine& machine, const ArtefactMeasurement& m) {
  const auto& p = m.placement;
  std::string out = fmt::format("# artefact: {}\n# dimension: {}\n# probed: {}\n", m.artefact.name, m.artefact.dimension, probedName(p.probed));
  const auto& a = m.alignment;
  if (a.method == AlignmentMethod::ThreePoint) {
    std::string ids;
    for (const int f : a.features)
      if (f >= 0) ids += (ids.empty() ? " " : ", ") + m.artefact.features[static_cast<size_t>(f)].id;
    out += "# alignment: three-point" + ids + "\n";
  } else {
    out += fmt::format("# alignment: {}\n", a.method == AlignmentMethod::LeastSquares ? "least-squares" : "least-squares-scaled");
  }
  out += probingHeaderText(machine, {.origin = p.origin, .u = p.u, .v = p.v, .stylus = p.stylus, .pose = p.fixedAxes,
                                     .temperatures = m.temperatures, .probe = m.probe, .simulation = m.simulation});
  out += "feature,u,v,w,U,x,y,z\n";
  for (size_t k = 0; k < m.artefact.features.size(); ++k) {
    const auto& f = m.artefact.features[k];
    out += fmt::format("{},{:.10f},{:.10f},{:.10f},", f.id, f.calibrated.x(), f.calibrated.y(), f.calibrated.z());
    if (m.certificateStated) out += fmt::format("{:.10g}", 2e3 * f.uncertainty);
    if (m.measured.rows() > 0) {
      const auto r = m.measured.row(static_cast<Eigen::Index>(k));
      out += fmt::format(",{:.10f},{:.10f},{:.10f}\n", r.x(), r.y(), r.z());
    } else {
      out += ",,,\n";
    }
  }
  return out;
}

ArtefactMeasurement artefactFromPlate(const PlateMeasurement& plate) {
  ArtefactMeasurement m;
  m.file = plate.file;
  const auto& p = plate.placement;
  m.placement = artefactPlacement(plate.plate, p);
  m.temperatures = plate.temperatures;
  if (plate.probe) m.probe = {plate.probe->x(), plate.probe->y()};
  m.simulation = plate.simulation;
  m.artefact = plateArtefact(plate.plate, plate.features);
  m.measured.resize(plate.measured.rows(), 3);
  for (Eigen::Index i = 0; i < plate.measured.rows(); ++i)
    m.measured.row(i) = (m.placement.origin + plate.measured(i, 0) * p.u + plate.measured(i, 1) * p.v).transpose();
  m.originLine = plate.originLine;
  m.artefactLine = plate.plateLine;
  return m;
}

ArtefactMeasurement readArtefactOrPlate(const Machine& machine, const std::string& path) {
  const std::string text = readTextFile(path);
  for (const auto& line : contentLines(text)) {
    const auto a = line.text.starts_with('#') ? commentAssignment(line.text) : std::nullopt;
    if (a && a->name == "plate") return artefactFromPlate(parsePlateMeasurement(machine, text, path));
    if (a && a->name == "artefact") break;
  }
  return parseArtefactMeasurement(machine, text, path);
}

}  // namespace mtacc
