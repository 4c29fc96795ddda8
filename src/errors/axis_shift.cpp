#include "mtacc/errors/axis_shift.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

// A cos(n (q - zero) + phase), n whole (a constant when n = 0).
struct Harmonic {
  double zero;
  int order;
  double amplitude, phase;
};

void add(ErrorFunction& f, const Harmonic& h) {
  if (h.amplitude == 0.0) return;
  if (h.order == 0) {
    f.add(PolynomialTerm{0.0, 1.0, {h.amplitude * std::cos(h.phase)}});
  } else {
    const bool negative = h.order < 0;  // cos(-m x + p) = cos(m x - p)
    f.add(HarmonicTerm{2 * kPi, h.zero, negative ? -h.order : h.order, h.amplitude, negative ? -h.phase : h.phase});
  }
}

// The term as a harmonic over one turn, or nullopt when it is none.
std::optional<Harmonic> overOneTurn(const ErrorTerm& term) {
  if (const auto* p = std::get_if<PolynomialTerm>(&term)) {
    for (size_t k = 1; k < p->coefficients.size(); ++k)
      if (p->coefficients[k] != 0.0) return std::nullopt;
    return Harmonic{0.0, 0, p->coefficients.empty() ? 0.0 : p->coefficients[0], 0.0};
  }
  if (const auto* h = std::get_if<HarmonicTerm>(&term)) {
    const double perTurn = h->order * 2 * kPi / h->period;
    if (std::abs(perTurn - std::round(perTurn)) > 1e-9) return std::nullopt;
    return Harmonic{h->zero, static_cast<int>(std::lround(perTurn)), h->amplitude, h->phase};
  }
  return std::nullopt;
}

}  // namespace

void addAxisShift(const Machine& machine, int axis, const std::array<ErrorFunction, 3>& shift, AxisErrors& errors) {
  const Axis& a = machine.axes[static_cast<size_t>(axis)];
  if (!a.isRotary()) throw InvalidInput(fmt::format("the axis-shift convention is for rotary axes, not {}", a.name));
  const Vec3 u = a.direction;
  // The workpiece side turns the other way (docs/conventions.md), so its R(q) is a turn by -q.
  const double sense = a.side == Side::Workpiece ? -1.0 : 1.0;
  for (int j = 0; j < 3; ++j) {
    // (I - R(q)) e_j = c (1 - cos q) - sense (u x e_j) sin q, with c = e_j - u u_j.
    const Vec3 e = Vec3::Unit(j);
    const Vec3 c = e - u * u[j];
    const Vec3 s = -sense * u.cross(e);
    for (const auto& term : shift[static_cast<size_t>(j)].terms()) {
      const auto g = overOneTurn(term);
      if (!g)
        throw InvalidInput(fmt::format("E{}{}: the axis-shift convention takes constants and harmonics whose period divides a turn",
                                       "XYZ"[j], a.name));
      // g cos q and g sin q as harmonics: cos q = cos((q - zero) + zero), sin q = cos((q - zero) + zero - 90 deg).
      const auto product = [&](double quarter, int n, double sign) {
        return Harmonic{g->zero, g->order + n, 0.5 * g->amplitude, g->phase + sign * (g->zero + quarter)};
      };
      for (int i = 0; i < 3; ++i) {
        auto& f = errors.motion[static_cast<size_t>(i)];
        add(f, Harmonic{g->zero, g->order, c[i] * g->amplitude, g->phase});
        for (const auto& h : {product(0.0, 1, 1.0), product(0.0, -1, -1.0)}) add(f, Harmonic{h.zero, h.order, -c[i] * h.amplitude, h.phase});
        for (const auto& h : {product(-0.5 * kPi, 1, 1.0), product(-0.5 * kPi, -1, -1.0)})
          add(f, Harmonic{h.zero, h.order, s[i] * h.amplitude, h.phase});
      }
    }
  }
}

}  // namespace mtacc
