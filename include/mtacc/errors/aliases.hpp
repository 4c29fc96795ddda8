#pragma once
// Error names in the notations of the sources, mapped onto ISO 230-1 names. The sign says
// how the source's value converts: iso = sign * source.
#include <optional>
#include <string>
#include <vector>

namespace mtacc {

struct Alias {
  std::string alias;     // as written in the source (ASCII form; Greek letters spelled out)
  std::string isoName;   // "X0B", "EXX", ...
  double sign;           // iso value = sign * source value
  std::string source;    // "seed 001 Table 3", ...
};

const std::vector<Alias>& aliasTable();
// Accepts the Greek forms too (δxBY, αBY, ...).
std::optional<Alias> findAlias(const std::string& name);

}  // namespace mtacc
