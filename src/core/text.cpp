#include "mtacc/core/text.hpp"

#include "mtacc/core/units.hpp"

#include <cmath>
#include <sstream>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::vector<std::string> splitList(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, separator))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> splitFields(const std::string& text, char separator) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const auto end = text.find(separator, start);
    out.push_back(trim(text.substr(start, end == std::string::npos ? std::string::npos : end - start)));
    if (end == std::string::npos) return out;
    start = end + 1;
  }
}

std::vector<TextLine> contentLines(const std::string& text) {
  std::vector<TextLine> lines;
  std::stringstream in(text);
  std::string raw;
  for (int n = 1; std::getline(in, raw); ++n)
    if (auto line = trim(raw); !line.empty()) lines.push_back({n, std::move(line)});
  return lines;
}

void readCommentedLines(const std::string& text, int& line, const std::function<void(const std::string&, const std::string&)>& comment,
                        const std::function<void(const std::string&)>& row) {
  for (const auto& [number, content] : contentLines(text)) {
    line = number;
    if (content[0] != '#') {
      row(content);
    } else if (const auto a = commentAssignment(content)) {
      comment(a->name, a->value);
    }
  }
}

std::optional<Assignment> commentAssignment(const std::string& line) {
  const auto colon = line.find(':');
  if (colon == std::string::npos) return std::nullopt;
  return Assignment{trim(line.substr(1, colon - 1)), trim(line.substr(colon + 1))};
}

std::vector<Assignment> parseAssignments(const std::string& text, const std::string& key) {
  std::vector<Assignment> out;
  for (const auto& item : splitList(text)) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError(InputLocation{"", 0, key}, "expected NAME=VALUE, got '" + item + "'");
    out.push_back({item.substr(0, eq), item.substr(eq + 1)});
  }
  return out;
}

double parseNumber(const std::string& text, const std::string& key) {
  double v = 0;
  size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError(InputLocation{"", 0, key}, "not a finite number: '" + text + "'");
  return v;
}

int parseCount(const std::string& text, const std::string& key, int min, int max) {
  const double v = parseNumber(text, key);
  if (v != std::floor(v) || v < min || v > max)
    throw InputError(InputLocation{"", 0, key}, "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
                                                    ", got '" + text + "'");
  return static_cast<int>(v);
}

Vec3 parseVector(const std::string& text, const std::string& key) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  if (items.size() != 3) throw InputError(InputLocation{"", 0, key}, "expected three numbers x,y,z");
  return {parseNumber(items[0], key), parseNumber(items[1], key), parseNumber(items[2], key)};
}

}  // namespace mtacc

namespace mtacc {

std::vector<double> parseLengthList(const std::string& text, size_t count, const std::string& key, const std::string& form,
                                    const std::string& example) {
  const auto parts = splitFields(text);
  if (parts.size() != count) throw InputError(InputLocation{"", 0, key}, "expected " + form);
  constexpr const char* kNumberCharacters = "+-.0123456789eE";
  const auto unitStart = parts.back().find_first_not_of(kNumberCharacters);
  if (unitStart == std::string::npos) throw InputError(InputLocation{"", 0, key}, "missing unit in '" + text + "' (e.g. '" + example + "')");
  const std::string unit = parts.back().substr(unitStart);
  std::vector<double> values;
  for (auto p : parts) {
    if (p.find_first_not_of(kNumberCharacters) == std::string::npos) p += unit;
    values.push_back(parseQuantityAs(p, Dimension::Length, key));
  }
  return values;
}

Vec3 parseLengths(const std::string& text, const std::string& key) {
  const auto v = parseLengthList(text, 3, key, "three values 'x, y, z mm'", "0, 0, 50 mm");
  return {v[0], v[1], v[2]};
}

}  // namespace mtacc
