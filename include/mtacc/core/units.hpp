#pragma once
// Quantities with units, as written in the input files: "10 um", "30 urad", "5 arcsec",
// "0.01 deg". Internally every length is in mm and every angle in rad.
#include <optional>
#include <string>
#include <string_view>

namespace mtacc {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kArcsec = kPi / 648000.0;
constexpr double kMicro = 1e-3;  // 1 um in mm

enum class Dimension { Length, Angle };

const char* toString(Dimension d);
const char* withArticle(Dimension d);  // "a length", "an angle"

struct Quantity {
  double value;         // in mm or rad
  Dimension dimension;
};

// Every quantity read lies within these magnitudes (mm, rad): a longer length or a larger
// angle is a typo or a unit mistake, and beyond them products of quantities overflow.
constexpr double kLargestLength = 1e6;         // 1 km
constexpr double kLargestAngle = 200.0 * kPi;  // 100 turns
double largestMagnitude(Dimension d);

// Parses "<number> <unit>". Returns nullopt with a reason when the text is not a quantity
// (no number, no unit, unknown unit, not finite, beyond largestMagnitude).
std::optional<Quantity> parseQuantity(std::string_view text, std::string* reason = nullptr);
// The same for a value of a known dimension; throws InputError naming `key` otherwise.
double parseQuantityAs(const std::string& text, Dimension expected, const std::string& key);

// Errors are shown in um and urad at every interface: the value in that unit, and its name.
double toDisplay(double value, Dimension d);  // mm -> um, rad -> urad
const char* displayUnit(Dimension d);         // "um" or "urad"

}  // namespace mtacc
