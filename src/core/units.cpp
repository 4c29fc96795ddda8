#include "mtacc/core/units.hpp"

#include <array>
#include <cmath>
#include <charconv>
#include <string>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

struct UnitDef {
  std::string_view name;
  double factor;
  Dimension dimension;
};

constexpr std::array<UnitDef, 17> kUnits{{
    {"nm", 1e-6, Dimension::Length},     {"um", 1e-3, Dimension::Length},
    {"µm", 1e-3, Dimension::Length},     {"mm", 1.0, Dimension::Length},
    {"cm", 10.0, Dimension::Length},     {"m", 1000.0, Dimension::Length},
    {"in", 25.4, Dimension::Length},     {"rad", 1.0, Dimension::Angle},
    {"mrad", 1e-3, Dimension::Angle},    {"urad", 1e-6, Dimension::Angle},
    {"µrad", 1e-6, Dimension::Angle},    {"um/m", 1e-6, Dimension::Angle},
    {"µm/m", 1e-6, Dimension::Angle},    {"mm/m", 1e-3, Dimension::Angle},
    {"deg", kDeg, Dimension::Angle},     {"arcmin", kPi / 10800.0, Dimension::Angle},
    {"arcsec", kArcsec, Dimension::Angle},
}};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

double largestMagnitude(Dimension d) { return d == Dimension::Length ? kLargestLength : kLargestAngle; }

const char* toString(Dimension d) { return d == Dimension::Length ? "length" : "angle"; }
const char* withArticle(Dimension d) { return d == Dimension::Length ? "a length" : "an angle"; }

std::optional<Quantity> parseQuantity(std::string_view text, std::string* reason) {
  auto fail = [&](std::string why) -> std::optional<Quantity> {
    if (reason) *reason = std::move(why);
    return std::nullopt;
  };
  text = trim(text);
  double number = 0.0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (!text.empty() && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, number);
  if (ec != std::errc() || ptr == begin) return fail("expected a number followed by a unit, got '" + std::string(text) + "'");
  if (!std::isfinite(number)) return fail("value is not finite: '" + std::string(text) + "'");
  std::string_view unit = trim(std::string_view(ptr, static_cast<size_t>(end - ptr)));
  if (unit.empty()) return fail("missing unit in '" + std::string(text) + "' (e.g. '10 um', '30 urad', '0.01 deg')");
  for (const auto& u : kUnits) {
    if (u.name != unit) continue;
    const Quantity q{number * u.factor, u.dimension};
    if (!(std::abs(q.value) <= largestMagnitude(q.dimension)))
      return fail("'" + std::string(text) + "' is out of range: " + withArticle(q.dimension) + " lies within " +
                  (q.dimension == Dimension::Length ? "±1 km" : "±100 turns (±36000 deg)"));
    return q;
  }
  return fail("unknown unit '" + std::string(unit) + "' (length: nm um mm cm m in; angle: rad mrad urad um/m mm/m deg arcmin arcsec)");
}

double parseQuantityAs(const std::string& text, Dimension expected, const std::string& key) {
  std::string reason;
  const auto q = parseQuantity(text, &reason);
  if (!q) throw InputError(InputLocation{"", 0, key}, reason);
  if (q->dimension != expected) throw InputError(InputLocation{"", 0, key}, std::string("expected ") + withArticle(expected));
  return q->value;
}

double toDisplay(double value, Dimension d) { return d == Dimension::Length ? value * 1e3 : value * 1e6; }
const char* displayUnit(Dimension d) { return d == Dimension::Length ? "um" : "urad"; }

}  // namespace mtacc
