#include "mtacc/workflows/thermal_drift.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/spindle_drift_yaml.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

double displayed(DriftDirection d, double value) { return value * displayScaleOf(d); }

bool changes(const Eigen::VectorXd& v) { return v.size() && v.maxCoeff() > v.minCoeff(); }

DriftTestKind kindOf(const DriftTestFile& test, int positionAxis) {
  if (positionAxis >= 0) return DriftTestKind::AxisMotion;
  if (!test.spindleSpeed) return DriftTestKind::Unstated;
  return test.spindleSpeed->maxCoeff() > 0 ? DriftTestKind::Spindle : DriftTestKind::EnvironmentalVariation;
}

int positionAxisOf(const DriftTestFile& test, const std::string& chosen) {
  const std::string axes = test.axes.empty() ? "none" : fmt::format("{}", fmt::join(test.axes, ", "));
  if (!chosen.empty()) {
    const auto it = std::find(test.axes.begin(), test.axes.end(), chosen);
    if (it == test.axes.end()) throw InputError({"", 0, "position"}, fmt::format("'{}': the file's axis positions are {}", chosen, axes));
    const int axis = static_cast<int>(it - test.axes.begin());
    if (!changes(test.positions.col(axis)))
      throw InputError({test.file, test.headerLine, chosen + "_mm"}, "the axis does not move: no position dependence to fit");
    return axis;
  }
  std::vector<int> moving;
  std::vector<std::string> names;
  for (size_t a = 0; a < test.axes.size(); ++a)
    if (changes(test.positions.col(static_cast<long>(a)))) {
      moving.push_back(static_cast<int>(a));
      names.push_back(test.axes[a]);
    }
  if (moving.size() > 1)
    throw InputError({"", 0, "position"}, fmt::format("axes {} move in {}: choose the one the drift depends on", fmt::join(names, ", "), test.file));
  return moving.empty() ? -1 : moving[0];
}

void refuseSpindleModel(const DriftTestFile& test, int positionAxis) {
  if (test.sensors.empty()) throw InputError({test.file, test.headerLine, "save-model"}, "no temperatures: the drift cannot be predicted from them");
  if (positionAxis >= 0)
    throw InputError({test.file, test.headerLine, "save-model"},
                     fmt::format("the models depend on the position of {}: a spindle's drift model is of a test at one place",
                                 test.axes[static_cast<size_t>(positionAxis)]));
}

}  // namespace

const char* nameOf(DriftTestKind kind) {
  switch (kind) {
    case DriftTestKind::Spindle: return "spindle thermal drift (ISO 230-3)";
    case DriftTestKind::AxisMotion: return "linear axis thermal drift (ISO 230-3)";
    case DriftTestKind::EnvironmentalVariation: return "environmental temperature variation (ISO 230-3 ETVE), the machine at rest";
    case DriftTestKind::Unstated: break;
  }
  return "thermal drift (no spindle speed recorded)";
}

const OptionSchema& driftTestSchema() {
  static const OptionSchema schema{
      "drift",
      {{.key = "test", .kind = OptionKind::Text, .help = "drift test (CSV, docs/file-formats.md \"Drift tests\")", .positional = true},
       {"sensor", OptionKind::Text, "temperature for the hysteresis; default: the one that changes most"},
       {.key = "folds", .kind = OptionKind::Count, .help = "cross-validation blocks", .defaultText = "5", .low = 2, .high = 100,
        .outOfRange = "must be from 2 to 100"},
       {.key = "max_sensors", .kind = OptionKind::Count, .help = "largest sensor set of a model", .defaultText = "8", .low = 0, .high = 64,
        .outOfRange = "must be from 0 to 64"},
       {"position", OptionKind::Text,
        "axis whose position (column AXIS_mm) the coefficients depend on; default: the one that moves, if one does"},
       {"save_model", OptionKind::Text,
        "write the models as the spindle's drift model (YAML) for a thermal state's spindle: (docs/file-formats.md)"}}};
  return schema;
}

DriftTestRequest driftTestRequest(const OptionValues& values) {
  const OptionReader read(driftTestSchema(), values);
  DriftTestRequest r;
  r.file = *read.text("test");
  r.hysteresisSensor = read.text("sensor").value_or("");
  r.selection.folds = *read.count("folds");
  r.selection.maximumSensors = *read.count("max_sensors");
  r.positionAxis = read.text("position").value_or("");
  r.saveModel = read.text("save_model").value_or("");
  return r;
}

DriftTestEvaluation evaluateDriftTest(const DriftTestRequest& request) {
  requireInRange(driftTestSchema().at("folds"), request.selection.folds);
  requireInRange(driftTestSchema().at("max_sensors"), request.selection.maximumSensors);
  DriftTestEvaluation out;
  out.test = readDriftTestCsv(request.file);
  const auto& test = out.test;
  try {
    out.drift = mandrelDrift(test.probes);
  } catch (const InvalidInput& e) {
    throw InputError({test.file, test.headerLine, "probe_z"}, e.what());
  }
  const long sensors = test.temperatures.cols();
  out.positionAxis = positionAxisOf(test, request.positionAxis);
  out.kind = kindOf(test, out.positionAxis);
  if (!request.saveModel.empty()) refuseSpindleModel(test, out.positionAxis);
  const Eigen::VectorXd position = out.positionAxis < 0 ? Eigen::VectorXd() : Eigen::VectorXd(test.positions.col(out.positionAxis));
  if (!request.hysteresisSensor.empty()) {
    const auto it = std::find(test.sensors.begin(), test.sensors.end(), request.hysteresisSensor);
    if (it == test.sensors.end())
      throw InputError({"", 0, "sensor"}, fmt::format("'{}': the file's temperatures are {}", request.hysteresisSensor,
                                                        test.sensors.empty() ? "none" : fmt::format("{}", fmt::join(test.sensors, ", "))));
    out.hysteresisSensor = static_cast<int>(it - test.sensors.begin());
  } else if (sensors > 0) {
    const Eigen::VectorXd ranges = test.temperatures.colwise().maxCoeff() - test.temperatures.colwise().minCoeff();
    ranges.maxCoeff(&out.hysteresisSensor);
  }
  auto selection = request.selection;
  selection.maximumSensors = static_cast<int>(std::min<long>(selection.maximumSensors, sensors));
  for (const auto direction : kDriftDirections) {
    const auto& series = out.drift[direction];
    if (!series) continue;
    DirectionEvaluation e;
    e.direction = direction;
    e.extremes = driftExtremes(*series, test.time);
    if (out.hysteresisSensor >= 0) e.hysteresis = driftHysteresis(*series, test.temperatures.col(out.hysteresisSensor));
    if (sensors > 0) {
      try {
        e.model = selectSensors({test.temperatures, *series, position}, selection);
      } catch (const InvalidInput& error) {
        throw InputError({test.file, test.headerLine, fmt::format("{} drift", nameOf(direction))}, error.what());
      }
    }
    out.directions.push_back(std::move(e));
  }
  if (!request.saveModel.empty()) {
    const auto& z = test.probes;
    writeFileAtomically(request.saveModel,
                        spindleDriftModelYaml(spindleDriftModel(out),
                                              fmt::format("The spindle's thermal drift from its temperatures, by mtacc drift --save-model from\n"
                                                          "{} ({}, {} samples over {:.2f} h):\n"
                                                          "drift = offset + sum over the sensors of per_kelvin x (T - reference); X and Y\n"
                                                          "at probe set 1 (z = {} mm in the test), tilts B = dx/dz and A = -dy/dz ({} mm apart).",
                                                          std::filesystem::path(test.file).filename().string(), nameOf(out.kind), test.time.size(),
                                                          (test.time[test.time.size() - 1] - test.time[0]) / 3600, z.z1, z.z2 - z.z1)),
                        "save-model");
  }
  return out;
}

SpindleDriftModel spindleDriftModel(const DriftTestEvaluation& evaluation) {
  const auto& test = evaluation.test;
  refuseSpindleModel(test, evaluation.positionAxis);
  SpindleDriftModel model;
  std::vector<int> named(test.sensors.size(), -1);  // the test's sensor -> the model's
  for (const auto& e : evaluation.directions) {
    DriftModel m = e.model->model;
    for (auto& s : m.sensors) {
      auto& index = named[static_cast<size_t>(s)];
      if (index < 0) {
        index = static_cast<int>(model.sensors.size());
        model.sensors.push_back(test.sensors[static_cast<size_t>(s)]);
      }
      s = index;
    }
    model.directions[static_cast<int>(e.direction)] = std::move(m);
  }
  return model;
}

nlohmann::json toJson(const DriftTestEvaluation& r, size_t seriesPoints) {
  const auto& test = r.test;
  nlohmann::json j{{"file", test.file},
                   {"samples", test.time.size()},
                   {"duration_s", test.time[test.time.size() - 1] - test.time[0]},
                   {"test", nameOf(r.kind)},
                   {"sensors", nlohmann::json::array()},
                   {"directions", nlohmann::json::array()}};
  for (size_t s = 0; s < test.sensors.size(); ++s) {
    const auto column = test.temperatures.col(static_cast<long>(s));
    j["sensors"].push_back({{"name", test.sensors[s]}, {"location", test.sensorLocations[s]}, {"rise_C", column.maxCoeff() - column[0]},
                            {"range_C", column.maxCoeff() - column.minCoeff()}});
  }
  if (r.hysteresisSensor >= 0) j["hysteresis_sensor"] = test.sensors[static_cast<size_t>(r.hysteresisSensor)];
  if (r.positionAxis >= 0) j["position_axis"] = test.axes[static_cast<size_t>(r.positionAxis)];
  for (const auto& e : r.directions) {
    const auto d = e.direction;
    nlohmann::json entry{{"direction", nameOf(d)},
                         {"unit", displayUnitOf(d)},
                         {"largest", displayed(d, e.extremes.largest)},
                         {"largest_at_s", e.extremes.time},
                         {"range", displayed(d, e.extremes.range)}};
    if (e.hysteresis)
      entry["hysteresis"] = {{"difference", displayed(d, e.hysteresis->difference)},
                             {"at_C", e.hysteresis->temperature},
                             {"bins", e.hysteresis->bins},
                             {"common_range_C", {e.hysteresis->commonLow, e.hysteresis->commonHigh}}};
    if (e.model) {
      const auto& m = e.model->model;
      const Eigen::VectorXd se = m.standardErrors(), positionSe = m.positionStandardErrors();
      nlohmann::json chosen = nlohmann::json::array();
      for (size_t s = 0; s < m.sensors.size(); ++s) {
        const auto i = static_cast<long>(s);
        chosen.push_back({{"sensor", test.sensors[static_cast<size_t>(m.sensors[s])]},
                          {"reference_C", m.referenceTemperatures[i]},
                          {"coefficient_per_K", displayed(d, m.coefficients[i])},
                          {"standard_error_per_K", displayed(d, se[i])}});
        if (m.positionDependent) {
          chosen.back()["coefficient_per_K_per_mm"] = displayed(d, m.positionCoefficients[i]);
          chosen.back()["standard_error_per_K_per_mm"] = displayed(d, positionSe[i]);
        }
      }
      nlohmann::json steps = nlohmann::json::array();
      for (const auto& step : e.model->steps)
        steps.push_back({{"sensor", step.sensor < 0 ? "(offset)" : test.sensors[static_cast<size_t>(step.sensor)]},
                         {"added", step.added},
                         {"cross_validated_rms", displayed(d, step.crossValidatedRms)}});
      entry["model"] = {{"offset", displayed(d, m.offset)},
                        {"sensors", chosen},
                        {"residual_rms", displayed(d, m.residualRms)},
                        {"residual_sigma", displayed(d, m.residualSigma)},
                        {"cross_validated_rms", displayed(d, e.model->crossValidatedRms)},
                        {"best_single_sensor", e.model->bestSingleSensor < 0 ? "" : test.sensors[static_cast<size_t>(e.model->bestSingleSensor)]},
                        {"best_single_sensor_rms", displayed(d, e.model->bestSingleSensorRms)},
                        {"steps", steps}};
      if (m.positionDependent) entry["model"]["offset_per_mm"] = displayed(d, m.offsetSlope);
    }
    j["directions"].push_back(entry);
  }
  if (seriesPoints == 0) return j;
  const long n = test.time.size();
  const long stride = std::max<long>(1, (n + static_cast<long>(seriesPoints) - 1) / static_cast<long>(seriesPoints));
  auto& series = j["series"] = {{"stride", stride}, {"time_s", nlohmann::json::array()}, {"temperatures_C", nlohmann::json::object()}};
  for (long k = 0; k < n; k += stride) series["time_s"].push_back(test.time[k]);
  for (size_t s = 0; s < test.sensors.size(); ++s) {
    auto& values = series["temperatures_C"][test.sensors[s]] = nlohmann::json::array();
    for (long k = 0; k < n; k += stride) values.push_back(test.temperatures(k, static_cast<long>(s)));
  }
  if (r.positionAxis >= 0) {
    auto& values = series["position_mm"] = nlohmann::json::array();
    for (long k = 0; k < n; k += stride) values.push_back(test.positions(k, r.positionAxis));
  }
  for (size_t e = 0; e < r.directions.size(); ++e) {
    const auto d = r.directions[e].direction;
    auto& entry = j["directions"][e];
    entry["series"] = nlohmann::json::array();
    const auto& model = r.directions[e].model;
    if (model) entry["predicted"] = entry["predicted_sigma"] = nlohmann::json::array();
    for (long k = 0; k < n; k += stride) {
      entry["series"].push_back(displayed(d, (*r.drift[d])[k]));
      if (!model) continue;
      const Eigen::VectorXd temperatures = test.temperatures.row(k).transpose();
      const double position = r.positionAxis < 0 ? 0.0 : test.positions(k, r.positionAxis);
      entry["predicted"].push_back(displayed(d, model->model.predict(temperatures, position)));
      entry["predicted_sigma"].push_back(displayed(d, model->model.predictionUncertainty(temperatures, position)));
    }
  }
  return j;
}

}  // namespace mtacc
