#include "mtacc/machine/structure_code.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

enum class TokenKind { Tool, Workpiece, Bed, Axis, Spindle };
struct Token {
  TokenKind kind;
  std::string name;
};

bool isAxisLetter(char c) { return std::string_view("XYZABCUVW").find(c) != std::string_view::npos; }

// Reads one axis name: a letter, optional digits, optional primes (which only say that the
// axis moves the workpiece; the side follows from the position in the code).
std::string readAxisName(const std::string& s, size_t& i) {
  std::string name(1, s[i++]);
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) name += s[i++];
  while (i < s.size() && (s[i] == '\'' || s[i] == '`')) ++i;
  return name;
}

std::vector<Token> tokenize(const std::string& s) {
  std::vector<Token> tokens;
  const size_t n = s.size();
  for (size_t i = 0; i < n;) {
    const char c = s[i];
    if (c == '-' || c == ' ') {
      ++i;
      continue;
    }
    const bool atEnd = tokens.empty() || i == s.find_last_not_of(" -");
    if ((c == 't' || c == 'T') && atEnd) {
      tokens.push_back({TokenKind::Tool, "t"});
      ++i;
    } else if ((c == 'w' || c == 'W') && atEnd) {
      tokens.push_back({TokenKind::Workpiece, "w"});
      ++i;
    } else if (c == 'b' || c == 'F') {
      tokens.push_back({TokenKind::Bed, "b"});
      ++i;
    } else if (c == '(') {
      const size_t close = s.find(')', i);
      if (close == std::string::npos) throw InvalidInput("unclosed '(' in structure code");
      size_t j = i + 1;
      if (j >= close || !isAxisLetter(s[j])) throw InvalidInput("'(...)' must hold the spindle's axis letter");
      std::string name = readAxisName(s, j);
      if (j != close) throw InvalidInput("unexpected text inside '(...)'");
      tokens.push_back({TokenKind::Spindle, name});
      i = close + 1;
    } else if (isAxisLetter(c)) {
      tokens.push_back({TokenKind::Axis, readAxisName(s, i)});
    } else {
      throw InvalidInput(std::string("unknown letter '") + c + "' in structure code");
    }
  }
  return tokens;
}

}  // namespace

StructureCode parseStructureCode(const std::string& text) {
  auto tokens = tokenize(text);
  if (tokens.size() < 3) throw InvalidInput("structure code too short: '" + text + "'");
  const bool toolFirst = tokens.front().kind == TokenKind::Tool;
  if (!toolFirst && tokens.front().kind != TokenKind::Workpiece)
    throw InvalidInput("structure code must start with t (tool) or w (workpiece)");
  const TokenKind last = toolFirst ? TokenKind::Workpiece : TokenKind::Tool;
  if (tokens.back().kind != last)
    throw InvalidInput(std::string("structure code must end with ") + (toolFirst ? "w" : "t"));
  if (!toolFirst) std::reverse(tokens.begin(), tokens.end());  // now tool first

  StructureCode code;
  code.text = text;
  const auto bed = std::find_if(tokens.begin(), tokens.end(), [](const Token& t) { return t.kind == TokenKind::Bed; });
  if (bed == tokens.end()) throw InvalidInput("structure code has no bed ('b' or 'F')");
  if (std::count_if(tokens.begin(), tokens.end(), [](const Token& t) { return t.kind == TokenKind::Bed; }) > 1)
    throw InvalidInput("structure code has more than one bed");

  std::set<std::string> seen;
  for (auto it = tokens.begin() + 1; it != bed; ++it) {
    if (it->kind == TokenKind::Spindle) {
      if (it != tokens.begin() + 1) throw InvalidInput("the spindle '(...)' must stand next to the tool");
      code.spindle = it->name;
      continue;
    }
    if (it->kind != TokenKind::Axis) throw InvalidInput("unexpected tool or workpiece mark inside the code");
    if (!seen.insert(it->name).second) throw InvalidInput("axis " + it->name + " appears twice");
    code.toolChain.insert(code.toolChain.begin(), it->name);  // stored from the bed outwards
  }
  for (auto it = bed + 1; it != tokens.end() - 1; ++it) {
    if (it->kind != TokenKind::Axis) throw InvalidInput("only axes may stand between the bed and the workpiece");
    if (!seen.insert(it->name).second) throw InvalidInput("axis " + it->name + " appears twice");
    code.workpieceChain.push_back(it->name);
  }
  if (code.toolChain.empty() && code.workpieceChain.empty())
    throw InvalidInput("structure code has no axes");
  return code;
}

std::string StructureCode::toolFirst() const {
  std::string s = "t";
  if (spindle) s += "-(" + *spindle + ")";
  for (auto it = toolChain.rbegin(); it != toolChain.rend(); ++it) s += "-" + *it;
  s += "-b";
  for (const auto& a : workpieceChain) s += "-" + a;
  return s + "-w";
}

}  // namespace mtacc
