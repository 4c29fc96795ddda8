#include "mtacc/workflows/acceptance.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/component_runs_csv.hpp"
#include "mtacc/io/measurement_csv.hpp"
#include "mtacc/io/tolerances_yaml.hpp"
#include "mtacc/measurement/circular_evaluation.hpp"
#include "mtacc/measurement/rotary_axis_tests.hpp"
#include "mtacc/procedures/geometric_tests.hpp"
#include "mtacc/workflows/positioning.hpp"
#include "mtacc/workflows/thermal_drift.hpp"

namespace mtacc {
namespace {

// Defaults of an instrument reading a range, where the test does not state its own: an R-test's
// or ballbar's stated accuracy (U = 1 um), half a um or arcsec for a direct measurement's reading.
constexpr double kRangeInstrumentU = 1e-3;
constexpr double kDirectReadingU = 0.5e-3, kDirectReadingAngleU = 0.5 * kArcsec;

std::vector<double> toVector(const Eigen::VectorXd& v, double scale) {
  std::vector<double> out(static_cast<size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) out[static_cast<size_t>(i)] = v[i] * scale;
  return out;
}

void positioning(const AcceptanceTestSpec& s, AcceptanceTestResult& r) {
  const auto e = evaluatePositioningFile({s.data, s.conditions, std::nullopt});
  const auto units = positioningUnits(e.test.axis);
  r.standard = "ISO 230-2";
  r.section = positioningToleranceTest(e.test.axis);
  r.instrument = e.conditions.instrument;
  r.defaulted = e.conditions.defaulted;
  r.uncertainty = e.uncertainty;
  r.unit = units.deviation;
  r.scale = units.deviationScale;
  r.detail = toJson(e);
}

// The instrument's standard uncertainty per reading and E_VE from the test's keys or the defaults.
RangeReadings rangeReadings(const AcceptanceTestSpec& s, Dimension dimension, double defaultU, std::optional<double> fileU,
                            const std::string& instrument, const std::string& planFile, std::vector<std::string>& defaulted) {
  const auto check = [&](const std::optional<Quantity>& q, const char* key) {
    if (q && q->dimension != dimension)
      throw InputError({planFile, s.line, s.key + "." + key},
                       fmt::format("test '{}' reads {}: expected {}", s.name, dimension == Dimension::Length ? "lengths" : "angles", withArticle(dimension)));
  };
  check(s.calibration, "calibration");
  check(s.drift, "drift");
  RangeReadings r;
  r.instrument = instrument;
  r.unit = dimension == Dimension::Length ? "um" : "arcsec";
  r.unitScale = dimension == Dimension::Length ? 1e3 : 1 / kArcsec;
  if (s.calibration) r.instrumentStandard = s.calibration->value / 2;
  else if (fileU) r.instrumentStandard = *fileU;
  else {
    r.instrumentStandard = defaultU / 2;
    r.instrumentDefaulted = true;
    defaulted.push_back("calibration");
  }
  r.drift = s.drift ? s.drift->value : 0.0;
  r.driftDefaulted = !s.drift;
  if (!s.drift) defaulted.push_back("drift");
  return r;
}

void rotary(const MachineSetup& setup, const AcceptancePlan& plan, const AcceptanceTestSpec& s, AcceptanceTestResult& r) {
  const auto nominal = setup.nominal();
  const MeasurementRun run = readMeasurementCsv(nominal, s.data);
  RotaryTestResult result;
  try {
    result = evaluateRotaryTest(nominal, run);
  } catch (const InvalidInput& e) {
    throw InputError({plan.file, s.line, s.key + ".data"}, s.data + ": " + e.reason());
  }
  r.standard = "ISO 10791-6";
  r.section = run.instrument == Instrument::RTest ? "rotary_rtest" : "rotary_ballbar";
  r.instrument = run.instrument == Instrument::RTest ? "R-test" : "ballbar";
  const RangeReadings readings = rangeReadings(s, Dimension::Length, kRangeInstrumentU, std::nullopt, r.instrument, plan.file, r.defaulted);
  std::vector<std::pair<std::string, double>> values;
  nlohmann::json ranges = nlohmann::json::object(), deviations = nlohmann::json::object();
  for (size_t q = 0; q < result.quantities.size(); ++q) {
    values.emplace_back(result.quantities[q], result.ranges[q]);
    ranges[result.quantities[q]] = result.ranges[q] / kMicro;
    deviations[result.quantities[q]] = toVector(result.series.col(static_cast<Eigen::Index>(q)), 1 / kMicro);
  }
  r.uncertainty = rangeUncertainty(values, 0.0, readings);
  r.detail = {{"run", run.name},         {"instrument", r.instrument}, {"poses", run.poses()},
              {"ranges", ranges},        {"deviations", deviations},   {"unit", "um"},
              {"axis_position_deg", toVector(result.position, 1 / kDeg)}};
}

void geometric(const MachineSetup& setup, const AcceptancePlan& plan, const AcceptanceTestSpec& s, AcceptanceTestResult& r) {
  const auto file = readComponentRuns(*setup.machine, s.data);
  GeometricTestResult g;
  try {
    g = evaluateGeometricTest(*setup.machine, file.component, file.runs);
  } catch (const InvalidInput& e) {
    throw InputError({plan.file, s.line, s.key + ".data"}, s.data + ": " + e.reason());
  }
  const bool angular = g.kind == GeometricTestKind::Angular;
  const Dimension dimension = angular ? Dimension::Angle : Dimension::Length;
  r.standard = "ISO 230-1";
  r.section = toleranceTestName(g.kind);
  r.instrument = file.instrument.empty() ? "direct measurement" : file.instrument;
  r.unit = angular ? "arcsec" : "um";
  r.scale = angular ? 1 / kArcsec : 1e3;
  RangeReadings readings = rangeReadings(s, dimension, angular ? 2 * kDirectReadingAngleU : 2 * kDirectReadingU, file.uncertainty,
                                         r.instrument, plan.file, r.defaulted);
  readings.scatter = g.repeatability;
  readings.readingsPerMean = g.readingsPerPosition;
  r.uncertainty = rangeUncertainty(g.quantities, g.measuredLength, readings);
  r.detail = {{"component", g.component},
              {"kind", r.section},
              {"unit", r.unit},
              {"positions_mm", g.positions},
              {"mean", toVector(g.mean, r.scale)},
              {"measured_length_mm", g.measuredLength}};
  if (g.kind == GeometricTestKind::Straightness) {
    r.detail["end_point_residual"] = toVector(g.endPointResidual, r.scale);
    r.detail["least_squares_residual"] = toVector(g.leastSquaresResidual, r.scale);
    r.detail["least_squares_slope_um_per_m"] = g.leastSquaresSlope * 1e6;
  }
}

// ISO 230-4: a ballbar circle's circular deviation G (the larger of its directions), circular
// hysteresis H (with both directions) and radial deviation F (the largest departure from the
// nominal radius, either sign); L the circle's diameter.
void circular(const MachineSetup& setup, const AcceptancePlan& plan, const AcceptanceTestSpec& s, AcceptanceTestResult& r) {
  const MeasurementRun run = readMeasurementCsv(setup.nominal(), s.data);
  if (run.instrument != Instrument::Ballbar || run.angle.empty())
    throw InputError({plan.file, s.line, s.key + ".data"},
                     s.data + ": an ISO 230-4 circular test is a ballbar circle (instrument: ballbar, with its angles)");
  CircularTestResult c;
  try {
    c = evaluateCircularTest(run);
  } catch (const InvalidInput& e) {
    throw InputError({plan.file, s.line, s.key + ".data"}, s.data + ": " + e.reason());
  }
  r.standard = "ISO 230-4";
  r.section = "circular";
  r.instrument = "ballbar";
  const RangeReadings readings = rangeReadings(s, Dimension::Length, kRangeInstrumentU, std::nullopt, r.instrument, plan.file, r.defaulted);
  double g = 0, f = 0;
  nlohmann::json directions = nlohmann::json::array();
  for (const auto& d : c.directions) {
    g = std::max(g, d.circularDeviation);
    f = std::max({f, std::abs(d.radialMax), std::abs(d.radialMin)});
    directions.push_back({{"sense", d.sense}, {"G", d.circularDeviation / kMicro}, {"F_max", d.radialMax / kMicro}, {"F_min", d.radialMin / kMicro}});
  }
  std::vector<std::pair<std::string, double>> values{{"G", g}, {"F", f}};
  if (c.bothDirections) values.insert(values.begin() + 1, {"H", c.hysteresis});
  r.uncertainty = rangeUncertainty(values, 2 * run.setup.length, readings);
  r.detail = {{"run", run.name}, {"unit", "um"}, {"directions", directions}, {"both_directions", c.bothDirections},
              {"radius_mm", run.setup.length}, {"deviation", toVector(run.readings.col(0), 1 / kMicro)}, {"sense", run.sense}};
  r.detail["angle_deg"] = toVector(Eigen::Map<const Eigen::VectorXd>(run.angle.data(), static_cast<Eigen::Index>(run.angle.size())), 1 / kDeg);
}

// ISO 230-3: the range of each displacement the probes give over the test (the tilts are in the
// detail, not toleranced); the drift is the measurand, so no environmental variation term.
void drift(const AcceptancePlan& plan, const AcceptanceTestSpec& s, AcceptanceTestResult& r) {
  DriftTestRequest request;
  request.file = s.data;
  const auto e = evaluateDriftTest(request);
  r.standard = "ISO 230-3";
  r.section = "thermal_drift";
  r.instrument = "displacement sensors";
  RangeReadings readings = rangeReadings(s, Dimension::Length, kRangeInstrumentU, std::nullopt, r.instrument, plan.file, r.defaulted);
  readings.environmentalVariation = false;
  std::erase(r.defaulted, "drift");
  std::vector<std::pair<std::string, double>> values;
  nlohmann::json tilts = nlohmann::json::object();
  for (const auto& d : e.directions) {
    if (isTilt(d.direction)) tilts[nameOf(d.direction)] = {{"range", d.extremes.range * 1e6}, {"unit", "urad"}};
    else values.emplace_back(nameOf(d.direction), d.extremes.range);
  }
  if (values.empty()) throw InputError({plan.file, s.line, s.key + ".data"}, s.data + ": the drift test gives no displacement (X, Y or Z) to judge");
  r.uncertainty = rangeUncertainty(values, 0.0, readings);
  r.detail = toJson(e, 2000);
  r.detail["tilts"] = tilts;
}

}  // namespace

Verdict AcceptanceResult::overall() const {
  std::vector<Verdict> each;
  for (const auto& t : tests) each.push_back(t.conformance.overall());
  return combined(each);
}

const OptionSchema& acceptanceSchema() {
  static const OptionSchema schema{
      "acceptance",
      {{.key = "tests", .kind = OptionKind::Text, .help = "the acceptance tests file (YAML, docs/file-formats.md \"Acceptance tests\")",
        .required = true},
       {"html", OptionKind::Text, "write the HTML acceptance report there (built by the Python package)"}}};
  return schema;
}

AcceptanceResult runAcceptance(const MachineSetup& setup, const std::string& testsFile) {
  const auto plan = loadAcceptancePlan(testsFile);
  AcceptanceResult out;
  out.machine = setup.machine->name;
  out.title = plan.title;
  out.file = plan.file;
  for (const auto& s : plan.tests) {
    AcceptanceTestResult r;
    r.spec = s;
    switch (s.type) {
      case AcceptanceTestType::Positioning:
        positioning(s, r);
        break;
      case AcceptanceTestType::Rotary:
        rotary(setup, plan, s, r);
        break;
      case AcceptanceTestType::Geometric:
        geometric(setup, plan, s, r);
        break;
      case AcceptanceTestType::Circular:
        circular(setup, plan, s, r);
        break;
      case AcceptanceTestType::Drift:
        drift(plan, s, r);
        break;
    }
    const auto tolerancesFile = s.tolerances ? s.tolerances : plan.tolerances;
    if (!tolerancesFile)
      throw InputError({plan.file, s.line, s.key + ".tolerances"},
                       fmt::format("test '{}' has no tolerance file: give tolerances: for it or for the file", s.name));
    auto tolerances = loadTolerances(*tolerancesFile);
    if (plan.decisionRule) tolerances.rule = *plan.decisionRule;
    r.conformance = judge(r.uncertainty, tolerances, r.section);
    out.tests.push_back(std::move(r));
  }
  return out;
}

nlohmann::json toJson(const AcceptanceResult& a) {
  nlohmann::json tests = nlohmann::json::array(), summary = nlohmann::json::array();
  for (const auto& t : a.tests) {
    const char* const types[] = {"positioning", "rotary", "geometric", "circular", "drift"};
    const char* type = types[static_cast<int>(t.spec.type)];
    tests.push_back({{"name", t.spec.name},
                     {"type", type},
                     {"standard", t.standard},
                     {"section", t.section},
                     {"data", t.spec.data},
                     {"unit", t.unit},
                     {"instrument", t.instrument},
                     {"defaulted", t.defaulted},
                     {"uncertainty", toJson(t.uncertainty, t.scale)},
                     {"conformance", toJson(t.conformance, t.scale)},
                     {"detail", t.detail}});
    for (const auto& v : t.conformance.verdicts)
      summary.push_back({{"test", t.spec.name},
                         {"standard", t.standard},
                         {"quantity", v.quantity},
                         {"value", v.value * t.scale},
                         {"U", v.expanded * t.scale},
                         {"tolerance", v.tolerance * t.scale},
                         {"unit", t.unit},
                         {"verdict", toString(v.verdict)}});
  }
  return {{"machine", a.machine}, {"title", a.title}, {"file", a.file}, {"overall", toString(a.overall())},
          {"summary", summary},   {"tests", tests}};
}

}  // namespace mtacc
