#pragma once
// Reading YAML with messages that name file, line and key. Private to the library.
#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/transform.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc::yamlin {

struct Context {
  std::string file;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& what) const;
  InputLocation at(const YAML::Node& node, const std::string& key) const;
};

// Loads a YAML document from a file (or from text), turning parser errors into InputError.
YAML::Node loadText(const std::string& text, const std::string& sourceName);

// A missing key's node answers IsSequence() with an exception: these ask IsDefined() first.
inline bool isSequence(const YAML::Node& node) { return node.IsDefined() && node.IsSequence(); }
inline bool isMap(const YAML::Node& node) { return node.IsDefined() && node.IsMap(); }

void rejectUnknownKeys(const Context& ctx, const YAML::Node& map, const std::string& path,
                       std::initializer_list<const char*> allowed);
std::string scalar(const Context& ctx, const YAML::Node& node, const std::string& key);
// true/false (also yes/no, on/off as YAML 1.1 has them).
bool boolean(const Context& ctx, const YAML::Node& node, const std::string& key);
double number(const Context& ctx, const YAML::Node& node, const std::string& key);
// A whole number in [minimum, maximum]; the range is in the message.
int wholeNumber(const Context& ctx, const YAML::Node& node, const std::string& key, int minimum, int maximum);
double quantity(const Context& ctx, const YAML::Node& node, const std::string& key, Dimension expected);
// A quantity that is a size or a divisor (a length, radius, period, pitch, scale): positive and
// at least 1 nm or 1 urad, so that nothing divides by a vanishing number.
double size(const Context& ctx, const YAML::Node& node, const std::string& key, Dimension expected);
// A quantity whose dimension is one of length or angle, chosen by the caller's context.
Quantity anyQuantity(const Context& ctx, const YAML::Node& node, const std::string& key);
// [x, y, z] of plain numbers, normalised; zero length is an error.
Vec3 unitVector(const Context& ctx, const YAML::Node& node, const std::string& key);
// [x mm, y mm, z mm]
Vec3 lengthVector(const Context& ctx, const YAML::Node& node, const std::string& key);

}  // namespace mtacc::yamlin
