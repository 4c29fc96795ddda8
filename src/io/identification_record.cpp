#include "mtacc/io/identification_record.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdlib>

#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {

EstimateUnit EstimateUnit::of(Dimension d) { return {toDisplay(1.0, d), displayUnit(d)}; }

EstimateUnit EstimateUnit::coefficient(Dimension value, bool rotaryPosition, int power) {
  EstimateUnit u = of(value);
  if (power == 0) return u;
  u.scale *= std::pow(rotaryPosition ? kDeg : 1.0, power);
  u.unit += std::string(rotaryPosition ? "/deg" : "/mm") + (power == 2 ? "^2" : "");
  return u;
}

namespace {

using yamlin::Context;

// "value unit" of a parameter in mtacc's units, and the unit's scale.
std::pair<double, double> estimate(const Context& ctx, const Machine& machine, const Parameter& p, const YAML::Node& node, const std::string& key) {
  const std::string text = yamlin::scalar(ctx, node, key);
  const auto space = text.find(' ');
  char* end = nullptr;
  const std::string number = text.substr(0, space);
  const double written = std::strtod(number.c_str(), &end);
  if (space == std::string::npos || end != number.c_str() + number.size() || !std::isfinite(written))
    ctx.fail(node, key, fmt::format("expected a finite number and its unit, e.g. '1.5 {}'", displayUnit(p.dimension)));
  const std::string unit = text.substr(space + 1);
  const bool rotary = machine.axes[static_cast<size_t>(p.axis)].isRotary();
  std::vector<std::string> fitting;
  for (int power = 0; power <= (p.kind == ParameterKind::Motion ? 2 : 0); ++power) {
    const auto u = EstimateUnit::coefficient(p.dimension, rotary, power);
    if (u.unit == unit) return {written / u.scale, u.scale};
    fitting.push_back(u.unit);
  }
  ctx.fail(node, key, fmt::format("the unit '{}' does not fit {} ({})", unit, p.name, fmt::join(fitting, ", ")));
}

}  // namespace

std::optional<ParameterCovariance> readParameterCovariance(const Machine& machine, const ErrorModel& errors, const std::string& path) {
  return parseParameterCovariance(machine, errors, readTextFile(path), path);
}

std::optional<ParameterCovariance> parseParameterCovariance(const Machine& machine, const ErrorModel& errors, const std::string& text,
                                                            const std::string& sourceName) {
  const Context ctx{sourceName};
  const YAML::Node root = yamlin::loadText(text, sourceName);
  if (!yamlin::isMap(root) || !yamlin::isMap(root["identification"])) return std::nullopt;
  const YAML::Node record = root["identification"];
  const YAML::Node estimates = record["estimates"], covariance = record["covariance"];
  if (!yamlin::isSequence(estimates)) ctx.fail(record, "identification.estimates", "expected a list of the estimates");
  const size_t n = estimates.size();
  if (!yamlin::isSequence(covariance) || covariance.size() != n)
    ctx.fail(yamlin::isSequence(covariance) ? covariance : record, "identification.covariance",
             fmt::format("expected {} rows, one per estimate", n));
  ParameterCovariance out;
  std::vector<size_t> kept;
  std::vector<double> scale;
  for (size_t k = 0; k < n; ++k) {
    const YAML::Node e = estimates[k];
    const std::string key = fmt::format("identification.estimates[{}]", k);
    if (!yamlin::isMap(e)) ctx.fail(e, key, "expected {parameter, value, standard_uncertainty}");
    const std::string name = yamlin::scalar(ctx, e["parameter"], key + ".parameter");
    std::optional<Parameter> p;
    try {
      p = findParameter(machine, errors, name);
    } catch (const InputError&) {
    }
    if (!p || !e["standard_uncertainty"] || e["standard_uncertainty"].IsNull()) {
      out.leftOut.push_back(name);
      continue;
    }
    scale.push_back(estimate(ctx, machine, *p, e["value"], key + ".value").second);
    estimate(ctx, machine, *p, e["standard_uncertainty"], key + ".standard_uncertainty");
    out.parameters.push_back(*p);
    kept.push_back(k);
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  out.covariance.resize(m, m);
  for (Eigen::Index a = 0; a < m; ++a) {
    const YAML::Node row = covariance[kept[static_cast<size_t>(a)]];
    const std::string key = fmt::format("identification.covariance[{}]", kept[static_cast<size_t>(a)]);
    if (!yamlin::isSequence(row) || row.size() != n) ctx.fail(row, key, fmt::format("expected a row of {} numbers", n));
    for (Eigen::Index b = 0; b < m; ++b) {
      const size_t column = kept[static_cast<size_t>(b)];
      const double c = yamlin::number(ctx, row[column], fmt::format("{}[{}]", key, column));
      if (a == b && !(c >= 0.0)) ctx.fail(row[column], fmt::format("{}[{}]", key, column), "a variance must not be negative");
      out.covariance(a, b) = c / (scale[static_cast<size_t>(a)] * scale[static_cast<size_t>(b)]);
    }
  }
  return out;
}

}  // namespace mtacc
