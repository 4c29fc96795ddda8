#pragma once
// Error names in the notations of the sources, mapped onto ISO 230-1 names. The sign says
// how the source's value converts: iso = sign * source. A few source errors act as a sum of
// ISO errors (seed 002's squareness errors turn the carried slides and the head together):
// those aliases have several terms, each receiving sign * value.
#include <optional>
#include <string>
#include <vector>

namespace mtacc {

struct AliasTerm {
  std::string isoName;  // "X0B", "EXX", ...
  double sign;          // iso value = sign * source value
};

struct Alias {
  std::string alias;  // as written in the source (ASCII form; Greek letters spelled out)
  std::vector<AliasTerm> terms;
  std::string source;  // "seed 001 Table 3", ...

  bool composite() const { return terms.size() > 1; }
  std::string isoExpression() const;  // "A0Y + A0B", "-X0B"
};

const std::vector<Alias>& aliasTable();
// Accepts the Greek forms too (δxBY, αBY, ...).
std::optional<Alias> findAlias(const std::string& name);
// iso value = sign * value given under `name`: the alias's sign, 1 for an ISO name.
double isoSign(const std::string& name);

}  // namespace mtacc
