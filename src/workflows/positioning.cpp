#include "mtacc/workflows/positioning.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/measurement_conditions_yaml.hpp"
#include "mtacc/io/positioning_files.hpp"
#include "mtacc/io/tolerances_yaml.hpp"

namespace mtacc {

PositioningUnits positioningUnits(PositioningAxis axis) {
  if (axis == PositioningAxis::Linear) return {1e3, "um", 1.0, "mm"};
  return {1.0 / kArcsec, "arcsec", 1.0 / kDeg, "deg"};
}

const OptionSchema& positioningSchema() {
  static const OptionSchema schema{
      "positioning",
      {{.key = "data", .kind = OptionKind::Text, .help = "ISO 230-2 KEY=value file or CSV target,cycle,forward,backward (docs/file-formats.md)",
        .positional = true},
       {.key = "conditions", .kind = OptionKind::Text,
        .help = "the instrument and environment (YAML, docs/file-formats.md \"Measurement conditions\"); default: the documented defaults"},
       {.key = "tolerances", .kind = OptionKind::Text,
        .help = "tolerances and decision rule (YAML, docs/file-formats.md \"Tolerances\"): a verdict per toleranced value"}}};
  return schema;
}

PositioningRequest positioningRequest(const OptionValues& values) {
  const OptionReader r(positioningSchema(), values);
  return {*r.text("data"), r.text("conditions"), r.text("tolerances")};
}

const char* positioningToleranceTest(PositioningAxis axis) {
  return axis == PositioningAxis::Linear ? "positioning" : "positioning_rotary";
}

PositioningEvaluation evaluatePositioningFile(const PositioningRequest& request) {
  PositioningEvaluation e;
  e.file = request.data;
  e.test = readPositioningTest(request.data);
  e.result = evaluatePositioning(e.test);
  e.conditionsFile = request.conditions.value_or("");
  e.conditions = request.conditions ? loadMeasurementConditions(*request.conditions)
                                      : defaultMeasurementConditions(e.test.axis == PositioningAxis::Rotary ? InstrumentType::Angle
                                                                                                            : InstrumentType::Laser);
  try {
    e.uncertainty = positioningUncertainty(e.test, e.result, e.conditions);
  } catch (const InvalidInput& error) {
    throw InputError({request.conditions.value_or(request.data), e.conditions.typeLine, "type"}, error.reason());
  }
  if (request.tolerances) e.conformance = judge(e.uncertainty, loadTolerances(*request.tolerances), positioningToleranceTest(e.test.axis));
  return e;
}

nlohmann::json toJson(const PositioningEvaluation& e) {
  const auto u = positioningUnits(e.test.axis);
  const auto& r = e.result;
  const double s = u.deviationScale;
  nlohmann::json j;
  j["file"] = e.file;
  j["name"] = e.test.name;
  j["axis"] = e.test.axis == PositioningAxis::Linear ? "linear" : "rotary";
  j["unit"] = u.deviation;
  j["target_unit"] = u.target;
  j["cycles"] = r.cycles;
  j["notes"] = r.notes;
  auto rows = [&](const Eigen::MatrixXd& x) {
    nlohmann::json out = nlohmann::json::array();
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      std::vector<double> row;
      for (Eigen::Index k = 0; k < x.cols(); ++k) row.push_back(x(i, k) * s);
      out.push_back(row);
    }
    return out;
  };
  j["deviations_forward"] = rows(e.test.forward);
  j["deviations_backward"] = rows(e.test.backward);
  nlohmann::json positions = nlohmann::json::array();
  for (const auto& p : r.positions)
    positions.push_back({{"target", p.target * u.targetScale},
                         {"mean_forward", p.meanForward * s},
                         {"mean_backward", p.meanBackward * s},
                         {"mean", p.mean * s},
                         {"reversal", p.reversal * s},
                         {"s_forward", p.sForward * s},
                         {"s_backward", p.sBackward * s},
                         {"repeatability_forward", p.repeatabilityForward * s},
                         {"repeatability_backward", p.repeatabilityBackward * s},
                         {"repeatability", p.repeatability * s}});
  j["positions"] = positions;
  j["axis_values"] = {{"A_forward", r.accuracyForward * s},
                      {"A_backward", r.accuracyBackward * s},
                      {"A", r.accuracy * s},
                      {"B", r.reversal * s},
                      {"B_mean", r.meanReversal * s},
                      {"E_forward", r.systematicForward * s},
                      {"E_backward", r.systematicBackward * s},
                      {"E", r.systematic * s},
                      {"M", r.meanDeviationRange * s},
                      {"R_forward", r.repeatabilityForward * s},
                      {"R_backward", r.repeatabilityBackward * s},
                      {"R", r.repeatability * s}};
  nlohmann::json uncertainty = toJson(e.uncertainty, s);
  uncertainty["measured_length"] = {{"value", e.uncertainty.measuredLength * u.targetScale}, {"unit", u.target}};
  uncertainty["conditions_file"] = e.conditionsFile;
  uncertainty["instrument"] = e.conditions.instrument;
  uncertainty["defaulted"] = e.conditions.defaulted;
  j["uncertainty"] = uncertainty;
  if (e.conformance) j["conformance"] = toJson(*e.conformance, s);
  return j;
}

}  // namespace mtacc
