#include "mtacc/workflows/cone_study.hpp"

#include <cmath>

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/cone_points_csv.hpp"
#include "mtacc/io/limits_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

nlohmann::json umArray(const std::vector<double>& mm) {
  nlohmann::json j = nlohmann::json::array();
  for (double v : mm) j.push_back(v * 1e3);
  return j;
}

nlohmann::json pointsJson(const std::vector<Vec3>& points) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& p : points) j.push_back(vectorJson(p));
  return j;
}

}  // namespace

const OptionSchema& coneSchema() {
  static const OptionSchema schema{
      "cone",
      {{"preset", OptionKind::Text, "tilting-table, swivel-head, double-pivot (Bossoni 2009 §3.6), seed000-comparison (its Table 3.6), nas979, or family (this machine's)"},
       {.key = "alpha", .kind = OptionKind::Number, .help = "Cone angle (half apex angle) [deg], negative: upside down", .defaultText = "45"},
       {.key = "beta", .kind = OptionKind::Number, .help = "Inclination of the cone axis [deg]", .defaultText = "30"},
       {.key = "radius", .kind = OptionKind::Number, .help = "TCP path radius [mm]", .defaultText = "40"},
       {.key = "centre", .kind = OptionKind::Text, .help = "Path centre x,y,z in the workpiece frame [mm]", .defaultText = "-65,0,150"},
       {.key = "gamma", .kind = OptionKind::Number, .help = "Turn of the inclined cone about the workpiece z [deg]", .defaultText = "0"},
       {"face_milling", OptionKind::Flag, "Tool normal to the cone surface instead of along the slant"},
       {.key = "points", .kind = OptionKind::Count, .help = "Points around the path", .defaultText = "720", .low = 8, .high = 1e6,
        .outOfRange = "must be between 8 and 1000000"},
       {.key = "chord_tolerance", .kind = OptionKind::Number, .help = "Choose the points for this chord error [mm] instead (0: use points)",
        .defaultText = "0"},
       {.key = "branch", .kind = OptionKind::Text, .help = "Tilt branch at phi = 0: negative (Bossoni 2009), positive or auto",
        .defaultText = "negative"},
       {.key = "feed", .kind = OptionKind::Number, .help = "Contouring feed [mm/min] for the axis speeds", .defaultText = "500"},
       {"single_errors", OptionKind::Flag, "Form error of each non-zero error alone"},
       {.key = "monte_carlo", .kind = OptionKind::Count, .help = "Number of Monte Carlo samples (e.g. 1000)", .defaultText = "0", .low = 0,
        .high = 1e6, .outOfRange = "must be from 0 to 1,000,000 samples"},
       {"limits", OptionKind::Text, "Error limits file for the Monte Carlo (default: Bossoni 2009 Table 3.9)"},
       {.key = "seed", .kind = OptionKind::Count, .help = "Random seed of the Monte Carlo", .defaultText = "1", .low = 0, .high = 2147483647,
        .outOfRange = "must be from 0 to 2147483647"},
       {"gcode", OptionKind::Text, "Write the NC program of the path to FILE"},
       {"cl", OptionKind::Text, "Write the CL data (phi, TCP, tool vector, surface normal) to FILE.csv"},
       {"measured", OptionKind::Text,
        "CMM points of the machined cone (CSV, docs/file-formats.md \"Measured cone frustum\"), evaluated beside the simulated form"}}};
  return schema;
}

ConeStudyRequest coneStudyRequest(const Machine& machine, const OptionValues& values) {
  const OptionReader read(coneSchema(), values);
  ConeStudyRequest r;
  if (auto preset = read.text("preset")) {
    if (*preset == "family") {
      const auto family = conePresetName(machine);
      if (!family) throw InputError(InputLocation{"", 0, "preset"}, "the machine does not have two rotary axes");
      preset = *family;
    }
    const auto spec = conePreset(*preset);
    if (!spec) throw InputError(InputLocation{"", 0, "preset"}, "unknown preset '" + *preset + "' (" + conePresetNames() + ", family)");
    r.spec = *spec;
  } else {
    r.spec.alpha = *read.number("alpha") * kDeg;
    r.spec.beta = *read.number("beta") * kDeg;
    r.spec.radius = *read.number("radius");
    r.spec.centre = parseVector(*read.text("centre"), "centre");
    r.spec.gamma = *read.number("gamma") * kDeg;
  }
  r.spec.faceMilling = read.flag("face_milling");
  r.points = *read.count("points");
  r.chordTolerance = *read.number("chord_tolerance");
  r.branch = parseTiltBranch(*read.text("branch"));
  r.feed = *read.number("feed");
  r.singleErrors = read.flag("single_errors");
  r.monteCarlo = *read.count("monte_carlo");
  r.limitsFile = read.text("limits").value_or("");
  r.seed = static_cast<std::uint64_t>(*read.count("seed"));
  r.measuredFile = read.text("measured").value_or("");
  return r;
}

ConeStudy coneStudy(const MachineSetup& setup, const ConeStudyRequest& options) {
  const Machine& m = *setup.machine;
  ConeStudy s;
  s.machine = setup.machine;
  s.options = options;
  const ConeSpec& spec = options.spec;
  auto require = [](bool ok, const char* key, const char* range) {
    if (!ok) throw InputError(InputLocation{"", 0, key}, range);
  };
  require(std::abs(spec.alpha) > 0 && std::abs(spec.alpha) < kPi / 2, "alpha", "must lie between -90 and 90 deg, not 0");
  require(std::abs(spec.beta) <= kPi / 2, "beta", "must lie within ±90 deg");
  require(std::abs(spec.gamma) <= 2 * kPi, "gamma", "must lie within ±360 deg");
  require(spec.radius > 0 && spec.radius <= kLargestLength, "radius", "must be positive (at most 1 km)");
  require(spec.centre.cwiseAbs().maxCoeff() <= kLargestLength, "centre", "must lie within ±1 km");
  require(options.feed > 0 && options.feed <= 1e6, "feed", "must be positive (at most 1e6 mm/min)");
  require(options.monteCarlo >= 0 && options.monteCarlo <= 1000000, "monte_carlo", "must be from 0 to 1,000,000 samples");
  require(options.chordTolerance >= 0, "chord_tolerance", "must not be negative (0: use the number of points)");
  s.options.points = options.chordTolerance > 0 ? pointsForChordTolerance(spec, options.chordTolerance) : options.points;
  if (s.options.points < 8 || s.options.points > 1000000)
    throw InputError(InputLocation{"", 0, "points"}, "must be between 8 and 1000000");
  const auto nominal = setup.nominal();
  s.path = conePath(spec, s.options.points);
  try {
    s.motion = coneMotion(nominal, spec, s.path, {options.branch, options.feed});
  } catch (const UnreachablePose& e) {
    throw UnreachableInput(InputLocation{"", 0, "centre"}, std::string("the path cannot be machined: ") + e.what());
  }
  s.closedForm = rotaryRangesClosedForm(spec.alpha, spec.beta);
  s.machineNormals.resize(static_cast<Eigen::Index>(s.path.normals.size()), 3);
  for (Eigen::Index i = 0; i < s.machineNormals.rows(); ++i)
    s.machineNormals.row(i) = (workpiecePose(nominal, s.motion.q.row(i).data(), nullptr).linear() *
                               s.path.normals[static_cast<size_t>(i)]).transpose();
  const auto nonZero = nonZeroParameters(m, setup.errors);
  if (!nonZero.empty()) {
    const auto actual = setup.actual();
    s.form = coneFormErrorExact(actual, spec, s.path, s.motion);
    s.firstOrderFormError = coneFormErrorFirstOrder(actual, nominal, s.path, s.motion).formError;
  }
  if (options.singleErrors) {
    for (const auto& p : nonZero) {
      auto r = coneFormErrorExact(compile(setup.machine, singleError(m, setup.errors, p, parameterValue(setup.errors, p))), spec,
                                  s.path, s.motion);
      const auto type = formErrorType(r.deviation);
      s.singleErrors.push_back({p.name, std::move(r), type});
    }
    std::stable_sort(s.singleErrors.begin(), s.singleErrors.end(),
                     [](const auto& a, const auto& b) { return a.form.formError > b.form.formError; });
  }
  if (options.monteCarlo > 0) {
    const bool bundled = options.limitsFile.empty() && options.limitsYaml.empty();
    s.limits = !options.limitsYaml.empty()
                   ? parseErrorLimits(m, options.limitsYaml, "limits")
                   : loadErrorLimits(m, bundled ? bundledDataDir() + "/limits/seed000-table3.9.yaml" : options.limitsFile,
                                     bundled ? AbsentAxes::LeaveOut : AbsentAxes::Refuse);
    s.monteCarlo = coneMonteCarlo(setup.machine, s.limits, spec, s.path, s.motion, options.monteCarlo, options.seed, options.progress);
    if (!s.limits.leftOut.empty())
      s.monteCarlo->notes.insert(s.monteCarlo->notes.begin(),
                                 fmt::format("{} limits of seed 000's tilting-table machine left out: their axes are not on this machine ({})",
                                             s.limits.leftOut.size(), fmt::join(s.limits.leftOut, ", ")));
  }
  if (!options.measuredFile.empty()) {
    try {
      s.measured = evaluateMeasuredCone(readConePoints(options.measuredFile), spec.alpha);
    } catch (const InvalidInput& e) {
      throw InputError(InputLocation{options.measuredFile, 0, "section"}, e.what());
    }
    s.comparison = compareForms(*s.measured, s.form ? s.form->deviation : std::vector<double>(s.path.phi.size(), 0.0), spec.radius);
  }
  return s;
}

ConeFormComparison compareForms(const MeasuredCone& measured, const std::vector<double>& simulated, double radius) {
  ConeFormComparison c;
  for (size_t k = 1; k < measured.cone.size(); ++k)
    if (std::abs(measured.cone[k].circle.radius - radius) < std::abs(measured.cone[c.section].circle.radius - radius)) c.section = k;
  const auto& m = measured.cone[c.section];
  // The path's points are evenly spaced over the turn from phi = 0: linear between neighbours.
  const auto n = simulated.size();
  double squares = 0;
  for (size_t i = 0; i < m.phi.size(); ++i) {
    const double at = m.phi[i] / (2 * kPi) * static_cast<double>(n);
    const auto below = static_cast<size_t>(std::floor(at)) % n;
    const double t = at - std::floor(at);
    c.simulated.push_back((1 - t) * simulated[below] + t * simulated[(below + 1) % n]);
    squares += std::pow(m.normal[i] - c.simulated.back(), 2);
  }
  const auto range = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end()); };
  c.measuredRange = range(m.normal);
  c.simulatedRange = range(simulated);
  c.rmsDifference = std::sqrt(squares / static_cast<double>(m.phi.size()));
  return c;
}

namespace {

nlohmann::json sectionJson(const MeasuredSection& m) {
  std::vector<double> phi;
  for (const double p : m.phi) phi.push_back(p / kDeg);
  return {{"name", m.name},
          {"diameter_mm", 2 * m.circle.radius},
          {"centre_mm", vectorJson(m.circle.centre)},
          {"height_mm", m.height},
          {"axis_offset_um", m.axisOffset * 1e3},
          {"circularity_least_squares_um", m.leastSquaresCircularity * 1e3},
          {"circularity_minimum_zone_um", m.minimumZoneCircularity * 1e3},
          {"minimum_zone_centre_mm", vectorJson(m.minimumZoneCentre)},
          {"phi_deg", phi},
          {"radial_um", umArray(m.radial)},
          {"normal_um", umArray(m.normal)}};
}

nlohmann::json measuredJson(const MeasuredCone& m, const ConeFormComparison& c, const std::string& file) {
  const auto optional = [](const std::optional<double>& v, double unit) { return v ? nlohmann::json(*v * unit) : nlohmann::json(nullptr); };
  nlohmann::json cone = nlohmann::json::array(), cylinder = nlohmann::json::array();
  for (const auto& s : m.cone) cone.push_back(sectionJson(s));
  for (const auto& s : m.cylinder) cylinder.push_back(sectionJson(s));
  return {{"file", file},
          {"axis_point_mm", vectorJson(m.axisPoint)},
          {"axis_direction", vectorJson(m.axisDirection)},
          {"half_angle_deg", optional(m.halfAngle, 1.0 / kDeg)},
          {"form_error_um", optional(m.formError, 1e3)},
          {"plane_flatness_um", m.planeNormal ? nlohmann::json(m.flatness * 1e3) : nlohmann::json(nullptr)},
          {"squareness_to_plane_urad", optional(m.squareness, 1e6)},
          {"coaxiality_um", optional(m.coaxiality, 1e3)},
          {"cone_sections", cone},
          {"cylinder_sections", cylinder},
          {"comparison",
           {{"section", m.cone[c.section].name},
            {"measured_form_um", c.measuredRange * 1e3},
            {"simulated_form_um", c.simulatedRange * 1e3},
            {"rms_difference_um", c.rmsDifference * 1e3},
            {"simulated_normal_um", umArray(c.simulated)}}}};
}

}  // namespace

nlohmann::json toJson(const ConeStudy& s) {
  const Machine& m = *s.machine;
  const ConeSpec& spec = s.options.spec;
  nlohmann::json j;
  j["machine"] = m.name;
  j["cone"] = {{"alpha_deg", spec.alpha / kDeg}, {"beta_deg", spec.beta / kDeg}, {"radius_mm", spec.radius},
               {"gamma_deg", spec.gamma / kDeg}, {"centre_mm", vectorJson(spec.centre)}, {"points", s.options.points},
               {"milling", spec.faceMilling ? "face" : "end"}, {"feed_mm_per_min", s.options.feed}};
  j["warnings"] = s.motion.warnings;
  for (size_t k = 0; k < s.motion.axes.size(); ++k) {
    const auto& a = s.motion.axes[k];
    const bool rotary = m.axes[k].isRotary();
    const double f = rotary ? 1.0 / kDeg : 1.0;
    std::vector<double> reversals;
    for (double p : a.reversalsPhi) reversals.push_back(p / kDeg);
    j["axes"].push_back({{"axis", a.axis}, {"unit", rotary ? "deg" : "mm"}, {"min", a.min * f}, {"max", a.max * f},
                         {"range", a.range * f}, {"reversals_phi_deg", reversals}, {"max_speed_per_s", a.maxSpeed * f / 60},
                         {"max_acceleration_per_s2", a.maxAcceleration * f / 3600}});
  }
  const auto& c = s.closedForm;
  j["closed_form"] = {{"case", c.caseName}, {"tilt_min_deg", c.tiltMin / kDeg}, {"tilt_max_deg", c.tiltMax / kDeg},
                      {"tilt_range_deg", c.tiltRange / kDeg}, {"rotary_range_deg", c.rotaryRange / kDeg}};
  nlohmann::json phi = nlohmann::json::array(), q = nlohmann::json::array(), normals = nlohmann::json::array();
  for (size_t i = 0; i < s.path.phi.size(); ++i) {
    phi.push_back(s.path.phi[i] / kDeg);
    nlohmann::json row = nlohmann::json::array();
    for (int k = 0; k < m.commandedCount(); ++k)
      row.push_back(m.axes[static_cast<size_t>(k)].isRotary() ? s.motion.q(static_cast<Eigen::Index>(i), k) / kDeg
                                                              : s.motion.q(static_cast<Eigen::Index>(i), k));
    q.push_back(row);
    normals.push_back(vectorJson(s.machineNormals.row(static_cast<Eigen::Index>(i)).transpose()));
  }
  j["path"] = {{"phi_deg", phi}, {"points_mm", pointsJson(s.path.points)}, {"tools", pointsJson(s.path.tools)},
               {"normals", pointsJson(s.path.normals)}, {"normals_machine", normals}, {"q", q}};
  if (s.form) {
    j["form_error_um"] = s.form->formError * 1e3;
    j["form_error_first_order_um"] = s.firstOrderFormError * 1e3;
    j["deviation_um"] = umArray(s.form->deviation);
    j["raw_deviation_um"] = umArray(s.form->rawDeviation);
  }
  for (const auto& e : s.singleErrors)
    j["single_errors"].push_back({{"error", e.name}, {"form_error_um", e.form.formError * 1e3}, {"type", toString(e.type)},
                                  {"deviation_um", umArray(e.form.deviation)}, {"raw_deviation_um", umArray(e.form.rawDeviation)}});
  if (s.monteCarlo) {
    const auto& st = s.monteCarlo->statistics;
    j["monte_carlo"] = {{"samples", s.options.monteCarlo}, {"limits", s.limits.file}, {"seed", s.options.seed},
                        {"min_um", st.min * 1e3}, {"lower_quartile_um", st.lowerQuartile * 1e3}, {"median_um", st.median * 1e3},
                        {"upper_quartile_um", st.upperQuartile * 1e3}, {"max_um", st.max * 1e3},
                        {"form_errors_um", umArray(s.monteCarlo->formErrors)}, {"notes", s.monteCarlo->notes}};
    // Each limit's drawn value per sample, in the unit of its error (um or urad).
    nlohmann::json names = nlohmann::json::array(), units = nlohmann::json::array(), values = nlohmann::json::array();
    Eigen::RowVectorXd scale(static_cast<Eigen::Index>(s.limits.limits.size()));
    for (size_t k = 0; k < s.limits.limits.size(); ++k) {
      const bool length = s.limits.limits[k].component < 3;
      names.push_back(s.limits.limits[k].key);
      units.push_back(length ? "um" : "urad");
      scale[static_cast<Eigen::Index>(k)] = length ? 1e3 : 1e6;
    }
    for (Eigen::Index i = 0; i < s.monteCarlo->drawn.rows(); ++i) {
      const Eigen::RowVectorXd row = s.monteCarlo->drawn.row(i).cwiseProduct(scale);
      values.push_back(std::vector<double>(row.data(), row.data() + row.size()));
    }
    j["monte_carlo"]["drawn"] = {{"names", names}, {"units", units}, {"values", values}};
  }
  if (s.measured) j["measured"] = measuredJson(*s.measured, *s.comparison, s.options.measuredFile);
  return j;
}

}  // namespace mtacc
