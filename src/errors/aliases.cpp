#include "mtacc/errors/aliases.hpp"

namespace mtacc {

const std::vector<Alias>& aliasTable() {
  // Seed 001 (Li, Sato et al.) writes the chain machine -> table (eq. 2) with the error
  // matrices applied to the machine point before the axis rotation: its errors are the
  // inverse of the axis-line displacement, hence sign -1 (checked by test Seed001.*).
  // Seed 003 (TU Eindhoven) uses the same element error transform as mtacc (eq. [3.8]).
  // Seed 002: checked term by term against its Table 5 (test Seed002.Table5*). Its
  // squareness errors M_YZ and M_XY (Eqs 5-6) turn the slide above them together with
  // everything it carries, which in ISO terms is the tilt of that slide's direction plus the
  // same turn of the B head: alphaYZ = A0Y + A0B, betaYZ = B0X + B0B, gammaXY = C0X + C0B.
  // Seed 004: names mapped as in shared/reference; signs follow the ISO sense (unchecked).
  static const std::vector<Alias> table = {
      {"dxBY", {{"X0B", -1}}, "seed 001 Table 3"},     {"dyBY", {{"Y0B", -1}}, "seed 001 Table 3"},
      {"dzBY", {{"Z0B", -1}}, "seed 001 Table 3"},     {"alphaBY", {{"A0B", -1}}, "seed 001 Table 3"},
      {"betaBY", {{"B0B", -1}}, "seed 001 Table 3"},   {"gammaBY", {{"C0B", -1}}, "seed 001 Table 3"},
      {"alphaCB", {{"A0C", -1}}, "seed 001 Table 3"},  {"dxCB", {{"X0C", -1}}, "seed 001 Table 3"},

      {"dxBT", {{"X0C1", 1}}, "seed 002 Table 1"},     {"dzBT", {{"Z0C1", 1}}, "seed 002 Table 1"},
      {"alphaBT", {{"A0C1", 1}}, "seed 002 Table 1"},  {"alphaXB", {{"A0B", 1}}, "seed 002 Table 1"},
      {"betaXB", {{"B0B", 1}}, "seed 002 Table 1"},    {"gammaXB", {{"C0B", 1}}, "seed 002 Table 1"},
      {"gammaXY", {{"C0X", 1}, {"C0B", 1}}, "seed 002 Table 1"},   {"alphaYZ", {{"A0Y", 1}, {"A0B", 1}}, "seed 002 Table 1"},
      {"betaYZ", {{"B0X", 1}, {"B0B", 1}}, "seed 002 Table 1"},    {"dxCZ", {{"X0C", 1}}, "seed 002 Table 1"},
      {"dyCZ", {{"Y0C", 1}}, "seed 002 Table 1"},      {"alphaCZ", {{"A0C", 1}}, "seed 002 Table 1"},
      {"betaCZ", {{"B0C", 1}}, "seed 002 Table 1"},

      {"xtx", {{"EXX", 1}}, "seed 003 §3.5"}, {"xty", {{"EYX", 1}}, "seed 003 §3.5"}, {"xtz", {{"EZX", 1}}, "seed 003 §3.5"},
      {"xrx", {{"EAX", 1}}, "seed 003 §3.5"}, {"xry", {{"EBX", 1}}, "seed 003 §3.5"}, {"xrz", {{"ECX", 1}}, "seed 003 §3.5"},
      {"ytx", {{"EXY", 1}}, "seed 003 §3.5"}, {"yty", {{"EYY", 1}}, "seed 003 §3.5"}, {"ytz", {{"EZY", 1}}, "seed 003 §3.5"},
      {"yrx", {{"EAY", 1}}, "seed 003 §3.5"}, {"yry", {{"EBY", 1}}, "seed 003 §3.5"}, {"yrz", {{"ECY", 1}}, "seed 003 §3.5"},
      {"ztx", {{"EXZ", 1}}, "seed 003 §3.5"}, {"zty", {{"EYZ", 1}}, "seed 003 §3.5"}, {"ztz", {{"EZZ", 1}}, "seed 003 §3.5"},
      {"zrx", {{"EAZ", 1}}, "seed 003 §3.5"}, {"zry", {{"EBZ", 1}}, "seed 003 §3.5"}, {"zrz", {{"ECZ", 1}}, "seed 003 §3.5"},
      {"btx", {{"EXB", 1}}, "seed 003 §3.5"}, {"bty", {{"EYB", 1}}, "seed 003 §3.5"}, {"btz", {{"EZB", 1}}, "seed 003 §3.5"},
      {"brx", {{"EAB", 1}}, "seed 003 §3.5"}, {"bry", {{"EBB", 1}}, "seed 003 §3.5"}, {"brz", {{"ECB", 1}}, "seed 003 §3.5"},
      {"ctx", {{"EXC", 1}}, "seed 003 §3.5"}, {"cty", {{"EYC", 1}}, "seed 003 §3.5"}, {"ctz", {{"EZC", 1}}, "seed 003 §3.5"},
      {"crx", {{"EAC", 1}}, "seed 003 §3.5"}, {"cry", {{"EBC", 1}}, "seed 003 §3.5"}, {"crz", {{"ECC", 1}}, "seed 003 §3.5"},

      {"dgammaY", {{"C0Y", 1}}, "seed 004 §3.3.2"},    {"dalphaZ", {{"A0Z", 1}}, "seed 004 §3.3.2"},
      {"dbetaZ", {{"B0Z", 1}}, "seed 004 §3.3.2"},     {"dbetaA", {{"B0A", 1}}, "seed 004 §3.3.2"},
      {"dgammaA", {{"C0A", 1}}, "seed 004 §3.3.2"},    {"dalphaC", {{"A0C", 1}}, "seed 004 §3.3.2"},
      {"dbetaC", {{"B0C", 1}}, "seed 004 §3.3.2"},     {"dyC", {{"Y0C", 1}}, "seed 004 §3.3.2"},
  };
  return table;
}

std::string Alias::isoExpression() const {
  std::string out;
  for (const auto& t : terms)
    out += (out.empty() ? (t.sign < 0 ? "-" : "") : (t.sign < 0 ? " - " : " + ")) + t.isoName;
  return out;
}

std::optional<Alias> findAlias(const std::string& name) {
  std::string ascii;
  for (size_t i = 0; i < name.size();) {
    auto startsWith = [&](const char* s) { return name.compare(i, std::char_traits<char>::length(s), s) == 0; };
    if (startsWith("δ")) { ascii += "d"; i += std::char_traits<char>::length("δ"); }
    else if (startsWith("α")) { ascii += "alpha"; i += std::char_traits<char>::length("α"); }
    else if (startsWith("β")) { ascii += "beta"; i += std::char_traits<char>::length("β"); }
    else if (startsWith("γ")) { ascii += "gamma"; i += std::char_traits<char>::length("γ"); }
    else if (name[i] == '_' || name[i] == '{' || name[i] == '}') ++i;
    else ascii += name[i++];
  }
  for (const auto& a : aliasTable())
    if (a.alias == ascii) return a;
  return std::nullopt;
}

double isoSign(const std::string& name) {
  const auto alias = findAlias(name);
  return alias && !alias->composite() ? alias->terms[0].sign : 1.0;
}

}  // namespace mtacc
