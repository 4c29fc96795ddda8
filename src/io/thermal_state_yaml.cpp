#include "mtacc/io/thermal_state_yaml.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/spindle_drift_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {

namespace {

std::vector<ScaleState> parseScales(const yamlin::Context& ctx, const Machine& machine, const YAML::Node& node) {
  std::vector<ScaleState> scales;
  if (!yamlin::isMap(node)) ctx.fail(node, "scales", "expected {AXIS: {sensors: [...], temperatures: [...], reference: P}}");
  for (const auto& entry : node) {
    const auto name = yamlin::scalar(ctx, entry.first, "scales");
    const std::string key = "scales." + name;
    const auto scale = entry.second;
    const int axis = machine.axisIndex(name);
    if (axis < 0 || machine.axes[static_cast<size_t>(axis)].type != AxisType::Linear || !machine.axes[static_cast<size_t>(axis)].travel)
      ctx.fail(entry.first, key, "not a linear axis with a travel of this machine");
    if (!yamlin::isMap(scale)) ctx.fail(scale, key, "expected {sensors: [...], temperatures: [...], reference: P}");
    yamlin::rejectUnknownKeys(ctx, scale, key, {"sensors", "temperatures", "reference", "expansion", "reference_temperature"});
    ScaleState state;
    state.axis = axis;
    const auto sensors = scale["sensors"], temperatures = scale["temperatures"];
    if (!yamlin::isSequence(sensors) || sensors.size() < 2 || sensors.size() > 64)
      ctx.fail(sensors ? sensors : scale, key + ".sensors", "expected 2 to 64 positions along the axis, e.g. [0 mm, 300 mm, 600 mm]");
    for (size_t i = 0; i < sensors.size(); ++i) {
      const double p = yamlin::quantity(ctx, sensors[i], key + ".sensors", Dimension::Length);
      if (!(std::abs(p) < 1e5)) ctx.fail(sensors[i], key + ".sensors", "a position within +-100 m");
      if (!state.sensors.positions.empty() && !(p > state.sensors.positions.back()))
        ctx.fail(sensors[i], key + ".sensors", "positions must increase");
      state.sensors.positions.push_back(p);
    }
    if (!yamlin::isSequence(temperatures) || temperatures.size() != sensors.size())
      ctx.fail(temperatures ? temperatures : scale, key + ".temperatures", fmt::format("expected {} temperatures in degC, one per sensor", sensors.size()));
    for (size_t i = 0; i < temperatures.size(); ++i) {
      const double t = yamlin::number(ctx, temperatures[i], key + ".temperatures");
      if (!(t >= -50 && t <= 150)) ctx.fail(temperatures[i], key + ".temperatures", "a temperature in -50 .. 150 degC");
      state.temperatures.push_back(t);
    }
    if (!scale["reference"]) ctx.fail(scale, key + ".reference", "missing (the position where the scale reads true, e.g. where the drift was measured)");
    state.sensors.referencePosition = yamlin::quantity(ctx, scale["reference"], key + ".reference", Dimension::Length);
    if (!(std::abs(state.sensors.referencePosition) < 1e5)) ctx.fail(scale["reference"], key + ".reference", "a position within +-100 m");
    if (const auto e = scale["expansion"]) {
      state.sensors.expansion = yamlin::number(ctx, e, key + ".expansion");
      if (!(std::abs(state.sensors.expansion) <= 1e-3)) ctx.fail(e, key + ".expansion", "a coefficient in 1/K within +-1e-3 (steel 11.5e-6)");
    }
    if (const auto t = scale["reference_temperature"]) {
      state.sensors.referenceTemperature = yamlin::number(ctx, t, key + ".reference_temperature");
      if (!(state.sensors.referenceTemperature >= -50 && state.sensors.referenceTemperature <= 150))
        ctx.fail(t, key + ".reference_temperature", "a temperature in -50 .. 150 degC");
    }
    scales.push_back(std::move(state));
  }
  return scales;
}

// The model's path is taken relative to the state's folder.
SpindleState parseSpindle(const yamlin::Context& ctx, const YAML::Node& node, const std::string& source) {
  if (!yamlin::isMap(node)) ctx.fail(node, "spindle", "expected {model: FILE, temperatures: {SENSOR: degC, ...}, probe_above_tcp: L}");
  yamlin::rejectUnknownKeys(ctx, node, "spindle", {"model", "temperatures", "probe_above_tcp"});
  if (!node["model"]) ctx.fail(node, "spindle.model", "missing (a spindle drift model, from mtacc drift TEST --save-model FILE)");
  const std::filesystem::path named = yamlin::scalar(ctx, node["model"], "spindle.model");
  const auto path = named.is_absolute() ? named : std::filesystem::path(source).parent_path() / named;
  SpindleState state;
  try {
    state.model = loadSpindleDriftModel(path.string());
  } catch (const InputError& e) {
    if (e.where().line == 0) ctx.fail(node["model"], "spindle.model", fmt::format("{}: {}", path.string(), e.reason()));
    throw;
  }
  const auto temperatures = node["temperatures"];
  if (!yamlin::isMap(temperatures))
    ctx.fail(temperatures ? temperatures : node, "spindle.temperatures", fmt::format("expected {{SENSOR: degC}} for the model's sensors ({})", fmt::join(state.model.sensors, ", ")));
  state.temperatures.resize(static_cast<long>(state.model.sensors.size()));
  for (size_t i = 0; i < state.model.sensors.size(); ++i) {
    const auto& name = state.model.sensors[i];
    const std::string key = "spindle.temperatures." + name;
    const auto t = temperatures[name];
    if (!t) ctx.fail(temperatures, key, "missing: the model needs " + fmt::format("{}", fmt::join(state.model.sensors, ", ")));
    const double value = yamlin::number(ctx, t, key);
    if (!(value >= -50 && value <= 150)) ctx.fail(t, key, "a temperature in -50 .. 150 degC");
    state.temperatures[static_cast<long>(i)] = value;
  }
  const bool tilts = state.model.directions[static_cast<int>(DriftDirection::A)] || state.model.directions[static_cast<int>(DriftDirection::B)];
  if (const auto h = node["probe_above_tcp"]) {
    state.probeAboveTcp = yamlin::quantity(ctx, h, "spindle.probe_above_tcp", Dimension::Length);
    if (!(std::abs(state.probeAboveTcp) < 1e4)) ctx.fail(h, "spindle.probe_above_tcp", "a length within +-10 m");
  } else if (tilts) {
    ctx.fail(node, "spindle.probe_above_tcp", "missing: the model tilts the spindle, so say where its X and Y drift was read: probe set 1's "
                                             "distance from the TCP towards the spindle, e.g. 100 mm");
  }
  return state;
}

}  // namespace

ThermalState parseThermalState(const Machine& machine, const std::string& text, const std::string& source) {
  const yamlin::Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  const char* expected = "expected a mapping with scales: {AXIS: {sensors, temperatures, reference}} and/or spindle: {model, temperatures}";
  if (!yamlin::isMap(root)) ctx.fail(root, "", expected);
  yamlin::rejectUnknownKeys(ctx, root, "", {"description", "scales", "spindle"});
  if (!root["scales"] && !root["spindle"]) ctx.fail(root, "", expected);
  ThermalState state;
  if (const auto scales = root["scales"]) state.scales = parseScales(ctx, machine, scales);
  if (const auto spindle = root["spindle"]) {
    if (machine.spindleIndex() < 0)
      ctx.fail(spindle, "spindle", "the machine has no spindle for the drift to move: name it in the structure code, e.g. t-(C)-Z-b-Y-X-w");
    state.spindle = parseSpindle(ctx, spindle, source);
  }
  return state;
}

ThermalState loadThermalState(const Machine& machine, const std::string& path) {
  return parseThermalState(machine, readTextFile(path), path);
}

}  // namespace mtacc
