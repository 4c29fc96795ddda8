#pragma once
// A workflow's options declared once: each key with its kind, unit, default and help. The CLI
// adds a flag per key (--key, '_' written '-'), Python passes its keyword arguments under the
// same keys, and both hand the text given to one reader that checks it and names the key.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/units.hpp"

namespace mtacc {

enum class OptionKind {
  Text,      // one string (a path, a name)
  List,      // strings, each value split at commas ("a,b" and "a", "b" alike)
  Numbers,   // real numbers, given as a List is, each within [low, high]
  Flag,      // true when given
  Count,     // a whole number within [low, high]
  Number,    // a real number within [low, high]
  Quantity,  // a length or an angle with its unit ("2 um"), within the magnitudes of core/units
};

struct OptionField {
  std::string key;           // snake_case
  OptionKind kind = OptionKind::Text;
  std::string help;          // one line; the unit and the default are added where they are shown
  std::string defaultText{};  // as a user would write it; empty: no default (the value is optional)
  Dimension dimension = Dimension::Length;  // for a Quantity
  // The range of a Count, a Number or a Quantity (mm, rad), and the message for a value outside
  // it; no range when outOfRange is empty.
  double low = 0, high = 0;
  bool lowExcluded = false;
  std::string outOfRange{};
  bool positional = false;  // the CLI takes it without a flag name; it must be given
  bool required = false;    // a flag that must be given
};

// `threads`, as every workflow that takes it declares it (core/parallel.hpp: 0 = every core).
OptionField threadsOption();

// Throws InputError naming the key with the field's outOfRange message when `value` (mm, rad for
// a Quantity) is outside its range: the check the reader makes, for a request built in code.
void requireInRange(const OptionField& field, double value);

struct OptionSchema {
  std::string name;  // the workflow's, for messages
  std::vector<OptionField> fields;

  const OptionField* find(const std::string& key) const;
  const OptionField& at(const std::string& key) const;  // a key the schema has
  std::vector<std::string> keys() const;
  // The schema of the keys named, in this order: a workflow that takes a subset of another's.
  OptionSchema subset(std::string name, const std::vector<std::string>& keys) const;
};

// The values given, by key: one string for a scalar, any number for a List; a Flag "true"/"false".
using OptionValues = std::map<std::string, std::vector<std::string>>;

// The help text of a field as the front ends show it: its line, the unit, the default.
std::string optionHelp(const OptionField& field);

// Reads `values` against `schema`. Throws InputError naming the key for a key the schema does
// not have, a positional key not given, a scalar given twice, or a value that is not of its kind
// or out of its range.
class OptionReader {
 public:
  OptionReader(const OptionSchema& schema, const OptionValues& values);

  std::optional<std::string> text(const std::string& key) const;
  std::vector<std::string> list(const std::string& key) const;
  std::vector<double> numbers(const std::string& key) const;
  bool flag(const std::string& key) const;
  std::optional<int> count(const std::string& key) const;
  std::optional<double> number(const std::string& key) const;
  std::optional<double> quantity(const std::string& key) const;  // mm or rad

 private:
  const OptionField& field(const std::string& key, OptionKind kind) const;
  std::optional<std::string> scalar(const OptionField& f) const;
  std::vector<std::string> items(const OptionField& f) const;

  const OptionSchema& schema_;
  const OptionValues& values_;
};

}  // namespace mtacc
