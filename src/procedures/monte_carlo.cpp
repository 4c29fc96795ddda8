#include "mtacc/procedures/monte_carlo.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mtacc/core/units.hpp"

namespace mtacc {

std::vector<AxisSpan> monteCarloSpans(const Machine& machine, const ErrorLimits& limits, const ConeMotion& motion,
                                      std::vector<std::string>& notes) {
  std::vector<AxisSpan> spans;
  for (size_t k = 0; k < motion.axes.size(); ++k) {
    const auto& a = motion.axes[k];
    if (a.moves) {
      spans.push_back({a.min, a.range});
      continue;
    }
    const Axis& axis = machine.axes[k];
    spans.push_back(harmonicSpan(axis));
    const bool scaled = std::any_of(limits.limits.begin(), limits.limits.end(), [&](const ErrorLimit& l) {
      return l.axis == static_cast<int>(k) && (l.kind == ErrorLimit::Linear || l.kind == ErrorLimit::Harmonic);
    });
    if (!scaled) continue;
    const double f = axis.isRotary() ? 1.0 / kDeg : 1.0;
    const char* unit = axis.isRotary() ? "deg" : "mm";
    notes.push_back(fmt::format("{} does not move on this path (at {:.6g} {}): its .lin and harmonic limits are taken over "
                                "[{:.6g}, {:.6g}] {} instead of its range on the path",
                                a.axis, a.min * f, unit, spans.back().min * f, (spans.back().min + spans.back().range) * f, unit));
  }
  return spans;
}

ErrorModel sampleErrors(const Machine& machine, const ErrorLimits& limits, const std::vector<AxisSpan>& spans,
                        std::mt19937_64& rng, std::vector<double>* drawn) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ErrorModel e = ErrorModel::zero(machine);
  if (drawn) drawn->clear();
  for (const auto& l : limits.limits) {
    const double v = l.lower + (l.upper - l.lower) * unit(rng);
    if (drawn) drawn->push_back(v);
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
  ConeMonteCarlo out;
  const auto spans = monteCarloSpans(*machine, limits, motion, out.notes);
  std::mt19937_64 rng(seed);
  out.drawn.resize(samples, static_cast<Eigen::Index>(limits.limits.size()));
  std::vector<double> drawn;
  for (int s = 0; s < samples; ++s) {
    const auto model = compile(machine, sampleErrors(*machine, limits, spans, rng, &drawn));
    out.drawn.row(s) = Eigen::Map<const Eigen::RowVectorXd>(drawn.data(), static_cast<Eigen::Index>(drawn.size()));
    out.formErrors.push_back(coneFormErrorExact(model, spec, path, motion).formError);
    if (progress && ((s + 1) % 50 == 0 || s + 1 == samples)) progress(s + 1, samples);
  }
  out.statistics = boxStatistics(out.formErrors);
  return out;
}

}  // namespace mtacc
