#include "mtacc/io/spindle_drift_yaml.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

std::string yamlScalar(const std::string& text) {
  YAML::Emitter e;
  e << text;
  return e.c_str();
}

}  // namespace

std::string spindleDriftModelYaml(const SpindleDriftModel& model, const std::string& comment) {
  std::string out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out += "# " + line + "\n";
  out += "directions:\n";
  for (int d = 0; d < 5; ++d) {
    if (!model.directions[d]) continue;
    const auto& m = *model.directions[d];
    const double s = displayScaleOf(kDriftDirections[d]);
    const char* unit = displayUnitOf(kDriftDirections[d]);
    out += fmt::format("  {}:\n    offset: {:.9g} {}\n    sensors:", nameOf(kDriftDirections[d]), m.offset * s, unit);
    out += m.sensors.empty() ? " []\n" : "\n";
    for (size_t i = 0; i < m.sensors.size(); ++i)
      out += fmt::format("      - {{name: {}, reference: {:.9g}, per_kelvin: {:.9g} {}}}\n", yamlScalar(model.sensors[static_cast<size_t>(m.sensors[i])]),
                         m.referenceTemperatures[static_cast<long>(i)], m.coefficients[static_cast<long>(i)] * s, unit);
    out += fmt::format("    residual_sigma: {:.9g} {}\n    covariance:   # of (offset, per_kelvin...), {}^2\n", m.residualSigma * s, unit, unit);
    for (long r = 0; r < m.covariance.rows(); ++r) {
      std::vector<std::string> row;
      for (long c = 0; c < m.covariance.cols(); ++c) row.push_back(fmt::format("{:.9g}", m.covariance(r, c) * s * s));
      out += fmt::format("      - [{}]\n", fmt::join(row, ", "));
    }
  }
  return out;
}

SpindleDriftModel parseSpindleDriftModel(const std::string& text, const std::string& source) {
  const yamlin::Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping with directions: {X: {offset, sensors, residual_sigma, covariance}, ...}");
  yamlin::rejectUnknownKeys(ctx, root, "", {"directions"});
  const auto directions = root["directions"];
  if (!yamlin::isMap(directions) || directions.size() == 0)
    ctx.fail(directions ? directions : root, "directions", "expected {X|Y|Z|A|B: {offset, sensors, residual_sigma, covariance}}");
  SpindleDriftModel model;
  for (const auto& entry : directions) {
    const auto name = yamlin::scalar(ctx, entry.first, "directions");
    const auto found = std::find_if(std::begin(kDriftDirections), std::end(kDriftDirections), [&](DriftDirection d) { return name == nameOf(d); });
    if (found == std::end(kDriftDirections)) ctx.fail(entry.first, "directions." + name, "not a drift direction (X, Y, Z, A or B)");
    const DriftDirection direction = *found;
    const int d = static_cast<int>(direction);
    const std::string key = "directions." + name;
    if (model.directions[d]) ctx.fail(entry.first, key, "given twice");
    const auto node = entry.second;
    if (!yamlin::isMap(node)) ctx.fail(node, key, "expected {offset, sensors, residual_sigma, covariance}");
    yamlin::rejectUnknownKeys(ctx, node, key, {"offset", "sensors", "residual_sigma", "covariance"});
    const Dimension dimension = isTilt(direction) ? Dimension::Angle : Dimension::Length;
    const double limit = isTilt(direction) ? 0.1 : 10.0;  // rad, mm: far beyond any drift
    const auto bounded = [&](const YAML::Node& n, const std::string& k, double bound) {
      if (!n) ctx.fail(node, k, "missing");
      const double v = yamlin::quantity(ctx, n, k, dimension);
      if (!(std::fabs(v) <= bound)) ctx.fail(n, k, fmt::format("a value within +-{} {}", bound * displayScaleOf(direction), displayUnitOf(direction)));
      return v;
    };
    DriftModel m;
    m.offset = bounded(node["offset"], key + ".offset", limit);
    const auto sensors = node["sensors"];
    if (!yamlin::isSequence(sensors) || sensors.size() > 64)
      ctx.fail(sensors ? sensors : node, key + ".sensors", "expected 0 to 64 of {name, reference, per_kelvin}");
    m.referenceTemperatures.resize(static_cast<long>(sensors.size()));
    m.coefficients.resize(static_cast<long>(sensors.size()));
    for (size_t i = 0; i < sensors.size(); ++i) {
      const auto s = sensors[i];
      const std::string sk = key + ".sensors";
      if (!yamlin::isMap(s)) ctx.fail(s, sk, "expected {name, reference, per_kelvin}");
      yamlin::rejectUnknownKeys(ctx, s, sk, {"name", "reference", "per_kelvin"});
      if (!s["name"]) ctx.fail(s, sk + ".name", "missing");
      const auto sensorName = yamlin::scalar(ctx, s["name"], sk + ".name");
      auto at = std::find(model.sensors.begin(), model.sensors.end(), sensorName);
      if (at == model.sensors.end()) at = model.sensors.insert(model.sensors.end(), sensorName);
      const int index = static_cast<int>(at - model.sensors.begin());
      if (std::count(m.sensors.begin(), m.sensors.end(), index)) ctx.fail(s["name"], sk + ".name", fmt::format("sensor '{}' given twice", sensorName));
      m.sensors.push_back(index);
      if (!s["reference"]) ctx.fail(s, sk + ".reference", "missing");
      const double t = yamlin::number(ctx, s["reference"], sk + ".reference");
      if (!(t >= -50 && t <= 150)) ctx.fail(s["reference"], sk + ".reference", "a temperature in -50 .. 150 degC");
      m.referenceTemperatures[static_cast<long>(i)] = t;
      m.coefficients[static_cast<long>(i)] = bounded(s["per_kelvin"], sk + ".per_kelvin", limit);
    }
    m.residualSigma = bounded(node["residual_sigma"], key + ".residual_sigma", limit);
    if (m.residualSigma < 0) ctx.fail(node["residual_sigma"], key + ".residual_sigma", "a standard deviation is not negative");
    const long n = 1 + m.coefficients.size();
    const auto covariance = node["covariance"];
    if (!yamlin::isSequence(covariance) || static_cast<long>(covariance.size()) != n)
      ctx.fail(covariance ? covariance : node, key + ".covariance", fmt::format("expected {} rows of {} numbers (offset, then each sensor)", n, n));
    m.covariance.resize(n, n);
    const double squared = displayScaleOf(direction) * displayScaleOf(direction);
    for (long r = 0; r < n; ++r) {
      const auto row = covariance[static_cast<size_t>(r)];
      if (!yamlin::isSequence(row) || static_cast<long>(row.size()) != n) ctx.fail(row, key + ".covariance", fmt::format("expected a row of {} numbers", n));
      for (long c = 0; c < n; ++c) m.covariance(r, c) = yamlin::number(ctx, row[static_cast<size_t>(c)], key + ".covariance") / squared;
    }
    const double largest = m.covariance.cwiseAbs().maxCoeff();
    if (!(largest <= limit * limit) || (m.covariance.diagonal().array() < 0).any() ||
        !((m.covariance - m.covariance.transpose()).cwiseAbs().maxCoeff() <= 1e-6 * largest))
      ctx.fail(covariance, key + ".covariance", "expected a symmetric matrix with a non-negative diagonal, within the values' range squared");
    model.directions[d] = std::move(m);
  }
  return model;
}

SpindleDriftModel loadSpindleDriftModel(const std::string& path) { return parseSpindleDriftModel(readTextFile(path), path); }

}  // namespace mtacc
