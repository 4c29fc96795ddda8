#include "mtacc/core/option_schema.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"

namespace mtacc {

const OptionField* OptionSchema::find(const std::string& key) const {
  const auto it = std::find_if(fields.begin(), fields.end(), [&](const OptionField& f) { return f.key == key; });
  return it == fields.end() ? nullptr : &*it;
}

const OptionField& OptionSchema::at(const std::string& key) const {
  const OptionField* f = find(key);
  if (!f) throw std::logic_error(fmt::format("{} declares no option '{}'", name, key));
  return *f;
}

OptionField threadsOption() {
  return {.key = "threads", .kind = OptionKind::Count, .help = "Threads (0: every core)", .defaultText = "0", .low = 0, .high = 1024,
          .outOfRange = "must be from 0 (every core) to 1024"};
}

void requireInRange(const OptionField& f, double value) {
  if (f.outOfRange.empty()) return;
  if (!((f.lowExcluded ? value > f.low : value >= f.low) && value <= f.high)) throw InputError({"", 0, f.key}, f.outOfRange);
}

std::vector<std::string> OptionSchema::keys() const {
  std::vector<std::string> out;
  for (const auto& f : fields) out.push_back(f.key);
  return out;
}

OptionSchema OptionSchema::subset(std::string subsetName, const std::vector<std::string>& keys) const {
  OptionSchema out{std::move(subsetName), {}};
  for (const auto& key : keys) out.fields.push_back(at(key));
  return out;
}

std::string optionHelp(const OptionField& f) {
  std::string help = f.help;
  if (f.kind == OptionKind::Quantity) help += f.dimension == Dimension::Length ? " (a length with its unit, e.g. 0.5um)" : " (an angle with its unit, e.g. 10urad)";
  if (f.kind == OptionKind::List || f.kind == OptionKind::Numbers) help += " (comma-separated, or the option repeated)";
  if (!f.defaultText.empty()) help += "; default " + f.defaultText;
  return help;
}

OptionReader::OptionReader(const OptionSchema& schema, const OptionValues& values) : schema_(schema), values_(values) {
  for (const auto& [key, given] : values) {
    const OptionField* f = schema.find(key);
    if (!f) throw InputError({"", 0, key}, fmt::format("not an option of {}; its options are: {}", schema.name, fmt::join(schema.keys(), ", ")));
    if (f->kind != OptionKind::List && f->kind != OptionKind::Numbers && given.size() > 1) throw InputError({"", 0, key}, "given more than once");
  }
  for (const auto& f : schema.fields)
    if ((f.positional || f.required) && !values.contains(f.key)) throw InputError({"", 0, f.key}, "is required");
}

const OptionField& OptionReader::field(const std::string& key, OptionKind kind) const {
  const OptionField& f = schema_.at(key);
  if (f.kind != kind) throw std::logic_error(fmt::format("option '{}' of {} is read as another kind than declared", key, schema_.name));
  return f;
}

std::optional<std::string> OptionReader::scalar(const OptionField& f) const {
  const auto it = values_.find(f.key);
  if (it != values_.end() && !it->second.empty()) return it->second.front();
  if (!f.defaultText.empty()) return f.defaultText;
  return std::nullopt;
}

std::optional<std::string> OptionReader::text(const std::string& key) const { return scalar(field(key, OptionKind::Text)); }

std::vector<std::string> OptionReader::items(const OptionField& f) const {
  std::vector<std::string> out;
  const auto it = values_.find(f.key);
  const std::vector<std::string> given = it != values_.end() ? it->second : splitList(f.defaultText);
  for (const auto& value : given)
    for (auto& item : splitList(value)) out.push_back(std::move(item));
  return out;
}

std::vector<std::string> OptionReader::list(const std::string& key) const { return items(field(key, OptionKind::List)); }

std::vector<double> OptionReader::numbers(const std::string& key) const {
  const OptionField& f = field(key, OptionKind::Numbers);
  std::vector<double> out;
  for (const auto& item : items(f)) {
    out.push_back(parseNumber(item, key));
    requireInRange(f, out.back());
  }
  return out;
}

bool OptionReader::flag(const std::string& key) const {
  const auto value = scalar(field(key, OptionKind::Flag));
  if (!value || *value == "false") return false;
  if (*value == "true") return true;
  throw InputError({"", 0, key}, "expected true or false, not '" + *value + "'");
}

std::optional<int> OptionReader::count(const std::string& key) const {
  const OptionField& f = field(key, OptionKind::Count);
  const auto value = scalar(f);
  if (!value) return std::nullopt;
  const double v = parseNumber(*value, key);
  if (v != std::floor(v)) throw InputError({"", 0, key}, "expected a whole number, not '" + *value + "'");
  if (std::abs(v) > std::numeric_limits<int>::max()) throw InputError({"", 0, key}, "'" + *value + "' is out of range: at most 2147483647 in size");
  requireInRange(f, v);
  return static_cast<int>(v);
}

std::optional<double> OptionReader::number(const std::string& key) const {
  const OptionField& f = field(key, OptionKind::Number);
  const auto value = scalar(f);
  if (!value) return std::nullopt;
  const double v = parseNumber(*value, key);
  requireInRange(f, v);
  return v;
}

std::optional<double> OptionReader::quantity(const std::string& key) const {
  const OptionField& f = field(key, OptionKind::Quantity);
  const auto value = scalar(f);
  if (!value) return std::nullopt;
  const double v = parseQuantityAs(*value, f.dimension, key);
  requireInRange(f, v);
  return v;
}

}  // namespace mtacc
