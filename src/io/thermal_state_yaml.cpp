#include "mtacc/io/thermal_state_yaml.hpp"

#include <fmt/format.h>

#include "mtacc/io/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {

std::vector<ScaleState> parseThermalState(const Machine& machine, const std::string& text, const std::string& source) {
  const yamlin::Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping with scales: {AXIS: {sensors, temperatures, reference}}");
  yamlin::rejectUnknownKeys(ctx, root, "", {"description", "scales"});
  std::vector<ScaleState> scales;
  const auto node = root["scales"];
  if (!yamlin::isMap(node)) ctx.fail(node ? node : root, "scales", "expected {AXIS: {sensors: [...], temperatures: [...], reference: P}}");
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

std::vector<ScaleState> loadThermalState(const Machine& machine, const std::string& path) {
  return parseThermalState(machine, readTextFile(path), path);
}

}  // namespace mtacc
