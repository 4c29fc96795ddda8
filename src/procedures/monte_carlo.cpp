#include "mtacc/procedures/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include "../io/yaml_input.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {

ErrorLimits loadErrorLimits(const Machine& machine, const std::string& path) {
  const yamlin::Context ctx{path};
  const auto root = yamlin::loadFile(path);
  if (!root.IsMap() || !root["limits"] || !root["limits"].IsMap()) ctx.fail(root, "limits", "expected a 'limits:' mapping");
  ErrorLimits out;
  out.file = path;
  static const std::regex pattern(R"(^(E([XYZABC])([A-Z]\d*))\.(lin|hyst|cyclic|(\d)harm)$)");
  const ErrorModel zero = ErrorModel::zero(machine);
  for (const auto& kv : root["limits"]) {
    const auto name = kv.first.as<std::string>();
    const std::string key = "limits." + name;
    ErrorLimit l;
    l.key = name;
    YAML::Node range = kv.second;
    std::smatch m;
    if (std::regex_match(name, m, pattern)) {
      l.axis = machine.axisIndex(m[3]);
      if (l.axis < 0) ctx.fail(kv.first, key, "unknown axis '" + m[3].str() + "'");
      l.component = static_cast<int>(std::string("XYZABC").find(m[2].str()[0]));
      const std::string type = m[4];
      l.kind = type == "lin" ? ErrorLimit::Linear : type == "hyst" ? ErrorLimit::Reversal
               : type == "cyclic" ? ErrorLimit::Cyclic : ErrorLimit::Harmonic;
      if (l.kind == ErrorLimit::Harmonic) l.order = std::stoi(m[5]);
      if (l.kind == ErrorLimit::Cyclic) {
        yamlin::rejectUnknownKeys(ctx, kv.second, key, {"range", "pitch"});
        const Dimension posDim = machine.axes[static_cast<size_t>(l.axis)].isRotary() ? Dimension::Angle : Dimension::Length;
        l.pitch = yamlin::quantity(ctx, kv.second["pitch"], key + ".pitch", posDim);
        if (!(l.pitch > 0)) ctx.fail(kv.second["pitch"], key + ".pitch", "must be positive");
        range = kv.second["range"];
      }
    } else {
      try {
        l.location = findParameter(machine, zero, name);
      } catch (const std::invalid_argument& e) {
        ctx.fail(kv.first, key, e.what());
      }
      if (l.location.kind != ParameterKind::Location) ctx.fail(kv.first, key, "expected a location error or NAME.lin/.hyst/.cyclic/.<k>harm");
      l.axis = l.location.axis;
      l.component = l.location.component;
    }
    const Dimension dim = l.component < 3 ? Dimension::Length : Dimension::Angle;
    if (!range.IsSequence() || range.size() != 2) ctx.fail(range, key, "expected [lower, upper] with units");
    l.lower = yamlin::quantity(ctx, range[0], key, dim);
    l.upper = yamlin::quantity(ctx, range[1], key, dim);
    if (l.lower > l.upper) ctx.fail(range, key, "lower limit above upper limit");
    out.limits.push_back(l);
  }
  return out;
}

ErrorModel sampleErrors(const Machine& machine, const ErrorLimits& limits, const std::vector<AxisSpan>& spans,
                        std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ErrorModel e = ErrorModel::zero(machine);
  for (const auto& l : limits.limits) {
    const double v = l.lower + (l.upper - l.lower) * unit(rng);
    if (l.kind == ErrorLimit::Location) {
      setParameterValue(e, l.location, v);
      continue;
    }
    auto& f = e.axes[static_cast<size_t>(l.axis)].motion[static_cast<size_t>(l.component)];
    const AxisSpan span = l.axis < static_cast<int>(spans.size()) ? spans[static_cast<size_t>(l.axis)] : AxisSpan{};
    switch (l.kind) {
      case ErrorLimit::Linear:
        f.add(PolynomialTerm{0.0, span.range, {0.0, v}});
        break;
      case ErrorLimit::Reversal:
        f.add(ReversalTerm{v});
        break;
      case ErrorLimit::Cyclic:
        f.add(HarmonicTerm{l.pitch, 0.0, 1, v, 2.0 * kPi * unit(rng), true});
        break;
      case ErrorLimit::Harmonic: {
        // cos(k pi (q - mid) / range + phase): k half waves over the range (eq. 3.63 for k = 1).
        const double phase = l.order >= 2 ? 2.0 * kPi * unit(rng) : 0.0;
        f.add(HarmonicTerm{2.0 * span.range / l.order, span.min + 0.5 * span.range, 1, v, phase});
        break;
      }
      case ErrorLimit::Location:
        break;
    }
  }
  return e;
}

ConeMonteCarlo coneMonteCarlo(std::shared_ptr<const Machine> machine, const ErrorLimits& limits, const ConeSpec& spec,
                              const ConePath& path, const ConeMotion& motion, int samples, std::uint64_t seed,
                              const std::function<void(int, int)>& progress) {
  std::vector<AxisSpan> spans;
  for (const auto& a : motion.axes) spans.push_back({a.min, a.range > 0 ? a.range : 1.0});
  std::mt19937_64 rng(seed);
  ConeMonteCarlo out;
  for (int s = 0; s < samples; ++s) {
    const auto model = compile(machine, sampleErrors(*machine, limits, spans, rng));
    out.formErrors.push_back(coneFormErrorExact(model, spec, path, motion).formError);
    if (progress && ((s + 1) % 50 == 0 || s + 1 == samples)) progress(s + 1, samples);
  }
  out.statistics = boxStatistics(out.formErrors);
  return out;
}

}  // namespace mtacc
