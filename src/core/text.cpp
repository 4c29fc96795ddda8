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

Vec3 parseLengths(const std::string& text, const std::string& key) {
  const auto parts = splitFields(text);
  if (parts.size() != 3) throw InputError(InputLocation{"", 0, key}, "expected three values 'x, y, z mm'");
  const auto unitStart = parts[2].find_first_not_of("+-.0123456789eE");
  if (unitStart == std::string::npos) throw InputError(InputLocation{"", 0, key}, "missing unit in '" + text + "' (e.g. '0, 0, 50 mm')");
  const std::string unit = parts[2].substr(unitStart);
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    std::string p = parts[static_cast<size_t>(k)];
    if (k < 2 && p.find_first_not_of("+-.0123456789eE") == std::string::npos) p += unit;
    v[k] = parseQuantityAs(p, Dimension::Length, key);
  }
  return v;
}

}  // namespace mtacc
