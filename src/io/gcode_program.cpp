#include "mtacc/io/gcode_program.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <array>
#include <cstdint>
#include <set>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr double kInch = 25.4;        // mm
constexpr double kLargestWord = 1e5;  // mm, deg or mm/min: beyond any machine's travel or feed
constexpr double kLargestNumber = 2147483647.0;  // N and O words
constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct Word {
  char letter;
  double value;
  std::string_view text;  // as written, for the kept words
};

struct Token {
  bool comment = false;
  std::string_view text;
  Word word{};
};

// G codes that change nothing mtacc evaluates and go to the compensated program as written:
// dwell, cutter compensation off, the first work offset, path control, canned cycle off, feed per
// minute.
const std::set<int> kKeptGcodes = {4, 40, 54, 61, 64, 80, 94};

// ASCII classes as the C locale has them, inline: the reader's inner loop runs over every
// character of a million-line program.
bool isBlank(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
bool isLetter(char c) { return (c | 0x20) >= 'a' && (c | 0x20) <= 'z'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

// The number at the start of `text`: an optional sign, then digits and points. `length` is how
// far they run; `value` is nullopt unless they are digits with at most one point, as
// std::from_chars reads them. When the digits make a whole number below 2^53 with at most 22 of
// them after the point, that number and the power of ten are both exact in a double and their
// quotient is the correctly rounded value (Clinger's fast path): every coordinate a program
// writes, read in the same pass that finds its end, at a fraction of from_chars's cost in the
// reader's inner loop. Longer numbers go to from_chars.
struct LeadingNumber {
  std::optional<double> value;
  size_t length = 0;
};

LeadingNumber leadingNumber(std::string_view text) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                            1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* p = text.data();
  const char* const end = p + text.size();
  const bool negative = p != end && *p == '-';
  if (p != end && (*p == '+' || *p == '-')) ++p;
  const char* const first = p;
  uint64_t whole = 0;  // wraps beyond 19 digits, which then go to from_chars
  while (p != end && isDigit(*p)) whole = whole * 10 + static_cast<uint64_t>(*p++ - '0');
  long afterPoint = 0;
  const bool point = p != end && *p == '.';
  if (point) {
    const char* const fraction = ++p;
    while (p != end && isDigit(*p)) whole = whole * 10 + static_cast<uint64_t>(*p++ - '0');
    afterPoint = p - fraction;
  }
  const long digits = p - first - (point ? 1 : 0);
  const char* const last = p;
  while (p != end && (isDigit(*p) || *p == '.')) ++p;  // a second point and what follows it
  const auto length = static_cast<size_t>(p - text.data());
  if (p != last || digits == 0) return {std::nullopt, length};
  if (digits <= 19 && whole <= (uint64_t{1} << 53) && afterPoint <= 22) {
    const double value = static_cast<double>(whole) / kPowersOfTen[afterPoint];
    return {negative ? -value : value, length};
  }
  double value = 0.0;
  const auto [stop, error] = std::from_chars(first, last, value);
  if (error != std::errc() || stop != last) return {std::nullopt, length};
  return {negative ? -value : value, length};
}

class LineReader {
 public:
  LineReader(const std::string& file, int line) : file_(file), line_(line) {}

  [[noreturn]] void fail(std::string_view key, const std::string& why) const { throw InputError({file_, line_, std::string(key)}, why); }

  // The line's words and comments into `out` (reused from line to line).
  void tokens(std::string_view text, std::vector<Token>& out) const {
    out.clear();
    size_t i = 0;
    while (i < text.size()) {
      const char c = text[i];
      if (isBlank(c)) {
        ++i;
      } else if (c == '(') {
        const size_t end = text.find(')', i);
        if (end == std::string_view::npos) fail("(", "a comment opened with '(' is not closed on its line");
        out.push_back({true, text.substr(i, end - i + 1), {}});
        i = end + 1;
      } else if (c == ';') {
        out.push_back({true, text.substr(i), {}});
        break;
      } else if (isLetter(c)) {
        const char letter = static_cast<char>(c & ~0x20);
        size_t j = i + 1;
        while (j < text.size() && text[j] == ' ') ++j;
        const auto [value, length] = leadingNumber(text.substr(j));
        const size_t end = j + length;
        const std::string_view number = text.substr(j, length);
        if (!value || !std::isfinite(*value))
          fail(std::string(1, letter), fmt::format("'{}' is not a word: a letter must be followed by a number", text.substr(i, std::max(end, i + 1) - i)));
        // Block and program numbers run as far as the controllers count (SINUMERIK, HEIDENHAIN: 2^31 - 1).
        const double largest = letter == 'N' || letter == 'O' ? kLargestNumber : kLargestWord;
        if (std::abs(*value) > largest) fail(std::string(1, letter), fmt::format("{}{} is beyond {:.15g}", letter, number, largest));
        out.push_back({false, text.substr(i, end - i), {letter, *value, text.substr(i, end - i)}});
        i = end;
      } else {
        fail(std::string(1, c), fmt::format("unexpected '{}': mtacc reads words (a letter and a number) and comments", c));
      }
    }
  }

 private:
  const std::string& file_;
  int line_;
};

struct ModalState {
  std::optional<MotionMode> motion;
  int plane = 17;
  bool inch = false;
  bool incremental = false;
  double feed = 0.0;  // mm/min; 0 until an F word
  double toolLength = 0.0;
};

int wholeNumber(const Word& w, const LineReader& reader) {
  if (w.value != std::round(w.value) || w.value < 0)
    reader.fail(w.text, fmt::format("{} must be a whole number", std::string(1, w.letter)));
  return static_cast<int>(w.value);
}

bool isAxisLetter(char c) { return std::string_view("XYZUVWABC").find(c) != std::string_view::npos; }

// Plane axes (first, second, normal) for G17, G18, G19 as letters; I, J, K are X, Y, Z offsets.
std::string_view planeLetters(int plane) { return plane == 17 ? "XYZ" : plane == 18 ? "ZXY" : "YZX"; }

void setArc(GcodeMove& move, const std::map<char, double>& offsets, std::optional<double> radius, int turns, const Machine& machine,
            int plane, const LineReader& reader, const std::string& key) {
  const std::string_view letters = planeLetters(plane);
  for (int k = 0; k < 3; ++k) {
    const int index = machine.commandedAxisIndex(std::string(1, letters[static_cast<size_t>(k)]));
    if (index < 0 || machine.axes[static_cast<size_t>(index)].isRotary())
      reader.fail(key, fmt::format("an arc in G{} needs the linear axes {}, {} and {}", plane, letters[0], letters[1], letters[2]));
    move.planeAxes[k] = index;
  }
  for (size_t k = 0; k < move.from.size(); ++k)
    if (machine.axes[k].isRotary() && move.from[k] != move.to[k]) reader.fail(key, "rotary axes cannot move in an arc: use G1");
  const auto a = static_cast<size_t>(move.planeAxes[0]), b = static_cast<size_t>(move.planeAxes[1]);
  const double x0 = move.from[a], y0 = move.from[b], x1 = move.to[a], y1 = move.to[b];
  const bool ccw = move.mode == MotionMode::ArcCounterClockwise;
  const bool closed = std::hypot(x1 - x0, y1 - y0) < 1e-9;
  if (radius) {
    const double chord = std::hypot(x1 - x0, y1 - y0);
    if (closed) reader.fail("R", "an arc given by R cannot end where it starts: give the centre with I, J, K for a full circle");
    const double r = std::abs(*radius);
    if (r < chord / 2.0 - 1e-6) reader.fail("R", fmt::format("R{:g} is shorter than half the chord ({:g} mm)", r, chord / 2.0));
    const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4.0));
    const double side = (ccw ? 1.0 : -1.0) * (*radius > 0 ? 1.0 : -1.0);
    move.centre[0] = (x0 + x1) / 2.0 - side * h * (y1 - y0) / chord;
    move.centre[1] = (y0 + y1) / 2.0 + side * h * (x1 - x0) / chord;
  } else {
    auto offset = [&](char letter) {
      const auto it = offsets.find(letter);
      return it == offsets.end() ? 0.0 : it->second;
    };
    move.centre[0] = x0 + offset(letters[0]);
    move.centre[1] = y0 + offset(letters[1]);
    const double r0 = std::hypot(x0 - move.centre[0], y0 - move.centre[1]), r1 = std::hypot(x1 - move.centre[0], y1 - move.centre[1]);
    if (r0 < 1e-6) reader.fail(key, "the arc's centre is its start point (zero radius)");
    if (std::abs(r1 - r0) > std::max(0.002, 1e-3 * r0))
      reader.fail(key, fmt::format("inconsistent arc: the start is {:.4f} mm from the centre, the end {:.4f} mm", r0, r1));
  }
  const double a0 = std::atan2(y0 - move.centre[1], x0 - move.centre[0]), a1 = std::atan2(y1 - move.centre[1], x1 - move.centre[0]);
  double sweep = closed ? kTwoPi : std::fmod((ccw ? a1 - a0 : a0 - a1) + 2.0 * kTwoPi, kTwoPi);
  sweep += kTwoPi * (turns - 1);
  move.sweep = ccw ? sweep : -sweep;
}

}  // namespace

struct GcodeLineReader::State {
  State(const std::string& f, const Machine& m, const GcodeReadOptions& o) : file(f), machine(m), options(o) {}
  std::string file;
  const Machine& machine;
  GcodeReadOptions options;
  std::array<int, 26> axisOf{};  // by address letter; -1 for none
  ModalState modal;
  AxisPositions position;
  int number = 0, moves = 0;
  std::vector<Token> tokens;
  GcodeMove move;
};

GcodeLineReader::GcodeLineReader(const std::string& file, const Machine& machine, const GcodeReadOptions& options)
    : s_(std::make_unique<State>(file, machine, options)) {
  const auto axes = static_cast<size_t>(machine.commandedCount());
  s_->axisOf.fill(-1);
  for (size_t k = 0; k < axes; ++k) {
    const Axis& a = machine.axes[k];
    if (a.name.size() == 1 && a.name[0] >= 'A' && a.name[0] <= 'Z') s_->axisOf[static_cast<size_t>(a.name[0] - 'A')] = static_cast<int>(k);
  }
  s_->position.assign(options.start.begin(), options.start.end());
  if (options.start.empty()) s_->position.assign(axes, 0.0);
  if (s_->position.size() != axes) throw InputError({file, 0, "start"}, fmt::format("the start pose needs {} axis positions", axes));
}

GcodeLineReader::~GcodeLineReader() = default;
GcodeLineReader::GcodeLineReader(GcodeLineReader&&) noexcept = default;

int GcodeLineReader::lines() const { return s_->number; }
int GcodeLineReader::moves() const { return s_->moves; }

const GcodeMove* GcodeLineReader::read(std::string_view raw, GcodeLine& line) {
  const std::string& file = s_->file;
  const Machine& machine = s_->machine;
  const GcodeReadOptions& options = s_->options;
  const auto& axisOf = s_->axisOf;
  ModalState& state = s_->modal;
  AxisPositions& position = s_->position;
  std::vector<Token>& tokens = s_->tokens;
  const int number = ++s_->number;
  line.number = number;
  line.kept.clear();
  line.sequence.clear();
  line.move = -1;
  const LineReader reader(file, number);
  const size_t first = raw.find_first_not_of(" \t");
  if (first != std::string_view::npos && raw[first] == '%') {
    line.kept.emplace_back(raw.substr(first));
    return nullptr;
  }
  if (first != std::string_view::npos && raw[first] == '/') reader.fail("/", "block delete ('/') is not supported: remove the block or its '/'");
  std::vector<std::string>& kept = line.kept;
  std::optional<MotionMode> motion;
  std::optional<int> plane, units, distance;
  std::optional<Word> toolOffset, lengthWord, turnsWord, feedWord;
  std::map<char, double> offsets;
  std::array<std::pair<char, double>, 9> axisWords{};  // X Y Z U V W A B C at most once each
  int axisCount = 0;
  std::optional<double> radius;
  uint32_t seen = 0;  // bit per letter
  reader.tokens(raw, tokens);
  for (const auto& t : tokens) {
    if (t.comment) {
      kept.emplace_back(t.text);
      continue;
    }
    const Word& w = t.word;
    const uint32_t bit = 1u << (w.letter - 'A');
    if (w.letter != 'G' && w.letter != 'M' && (seen & bit) != 0)
      reader.fail(w.text, fmt::format("{} is given twice on the line", std::string(1, w.letter)));
    seen |= bit;
    switch (w.letter) {
      case 'G': {
        const double code = w.value;
        auto group = [&](auto& slot, int value) {
          if (slot) reader.fail(w.text, "two G codes of the same modal group on one line");
          slot = value;
        };
        if (code == 0 || code == 1 || code == 2 || code == 3) {
          if (motion) reader.fail(w.text, "two motion G codes on one line");
          motion = code == 0 ? MotionMode::Rapid : code == 1 ? MotionMode::Linear : code == 2 ? MotionMode::ArcClockwise : MotionMode::ArcCounterClockwise;
        } else if (code == 17 || code == 18 || code == 19) {
          group(plane, static_cast<int>(code));
        } else if (code == 20 || code == 21) {
          group(units, static_cast<int>(code));
        } else if (code == 90 || code == 91) {
          group(distance, static_cast<int>(code));
        } else if (code == 43 || code == 49) {
          if (toolOffset) reader.fail(w.text, "two G codes of the same modal group on one line");
          toolOffset = w;
          kept.emplace_back(w.text);
        } else if (code == std::round(code) && kKeptGcodes.count(static_cast<int>(code))) {
          kept.emplace_back(w.text);
        } else {
          reader.fail(w.text, fmt::format("{} is not supported: mtacc reads G0-G3, G4, G17-G21, G40, G43, G49, G54, G61, G64, G80, G90, "
                                          "G91, G94 (tool-tip programs, canned cycles and other work offsets are refused)",
                                          w.text));
        }
        break;
      }
      case 'I': case 'J': case 'K': offsets[static_cast<char>('X' + (w.letter - 'I'))] = w.value; break;
      case 'R':
        if (w.value == 0) reader.fail(w.text, "an arc radius cannot be zero");
        radius = w.value;
        break;
      case 'F':
        if (w.value <= 0) reader.fail(w.text, "the feed must be positive");
        feedWord = w;
        break;
      case 'H': lengthWord = w; kept.emplace_back(w.text); break;
      case 'P': turnsWord = w; break;
      case 'N': line.sequence = w.text; break;
      case 'M': case 'S': case 'T': case 'O': kept.emplace_back(w.text); break;
      default:
        if (!isAxisLetter(w.letter)) reader.fail(w.text, fmt::format("the word {} is not supported", std::string(1, w.letter)));
        if (axisOf[static_cast<size_t>(w.letter - 'A')] < 0) reader.fail(w.text, fmt::format("the machine {} has no axis {}", machine.name, std::string(1, w.letter)));
        axisWords[static_cast<size_t>(axisCount++)] = {w.letter, w.value};
    }
  }
  // Execution order within a line (RS-274/NGC): feed, tool length, plane, units, distance, motion.
  if (units) state.inch = *units == 20;
  if (feedWord) state.feed = feedWord->value * (state.inch ? kInch : 1.0);
  if (toolOffset) {
    if (toolOffset->value == 43) {
      if (!lengthWord) reader.fail(toolOffset->text, "G43 needs H<tool number>");
      const int tool = wholeNumber(*lengthWord, reader);
      const auto it = options.toolLengths.find(tool);
      if (it == options.toolLengths.end())
        reader.fail(lengthWord->text, fmt::format("the length of tool {} is not given (--tool-length {}=<mm>)", tool, tool));
      state.toolLength = it->second;
    } else {
      if (lengthWord) reader.fail(lengthWord->text, "H goes with G43");
      state.toolLength = 0.0;
    }
  } else if (lengthWord) {
    reader.fail(lengthWord->text, "H goes with G43");
  }
  if (plane) state.plane = *plane;
  if (distance) state.incremental = *distance == 91;
  if (motion) state.motion = motion;
  const bool arcWords = !offsets.empty() || radius;
  if (turnsWord) {
    const bool isDwell = std::any_of(tokens.begin(), tokens.end(), [](const Token& t) { return !t.comment && t.word.letter == 'G' && t.word.value == 4; });
    if (isDwell) {
      kept.emplace_back(turnsWord->text);
    } else if (!(arcWords && state.motion && (*state.motion == MotionMode::ArcClockwise || *state.motion == MotionMode::ArcCounterClockwise))) {
      reader.fail(turnsWord->text, "P goes with G4 (dwell) or an arc (turns)");
    }
  }
  const bool moves = axisCount > 0 || (arcWords && state.motion && *state.motion != MotionMode::Rapid && *state.motion != MotionMode::Linear);
  const bool arc = state.motion && (*state.motion == MotionMode::ArcClockwise || *state.motion == MotionMode::ArcCounterClockwise);
  if (arcWords && (!moves || !arc)) reader.fail(offsets.empty() ? "R" : "I/J/K", "arc words without an arc (G2/G3)");
  if (moves) {
    if (!state.motion) reader.fail(std::string(1, axisWords[0].first), "axis words with no motion mode (G0, G1, G2, G3) in effect");
    GcodeMove& move = s_->move;
    move = GcodeMove{};
    move.line = number;
    move.mode = *state.motion;
    move.from = position;
    move.to = position;
    move.toolLength = state.toolLength;
    for (int w = 0; w < axisCount; ++w) {
      const auto [letter, value] = axisWords[static_cast<size_t>(w)];
      const auto k = static_cast<size_t>(axisOf[static_cast<size_t>(letter - 'A')]);
      const double v = machine.axes[k].isRotary() ? value * kDeg : value * (state.inch ? kInch : 1.0);
      move.to[k] = state.incremental ? position[k] + v : v;
    }
    if (const std::string beyond = machine.travelViolation({move.to.data(), move.to.size()}); !beyond.empty()) reader.fail(std::string(1, axisWords[0].first), beyond);
    if (move.mode != MotionMode::Rapid) {
      if (state.feed <= 0) reader.fail("F", "a feed move before any feed (F word)");
      move.feed = state.feed;
    }
    if (move.isArc()) {
      if (!offsets.empty() && radius) reader.fail("R", "an arc takes either R or I, J, K, not both");
      if (offsets.empty() && !radius) reader.fail("G2/G3", "an arc needs its centre (I, J, K) or its radius (R)");
      std::map<char, double> scaled;
      for (const auto& [axis, offset] : offsets) scaled[axis] = offset * (state.inch ? kInch : 1.0);
      const std::string_view letters = planeLetters(state.plane);
      for (const auto& [axis, offset] : scaled)
        if (axis == letters[2]) reader.fail(std::string(1, static_cast<char>('I' + (axis - 'X'))), fmt::format("no centre offset along {} in G{}", axis, state.plane));
      const int turns = turnsWord ? wholeNumber(*turnsWord, reader) : 1;
      if (turns < 1 || turns > 1000) reader.fail(turnsWord->text, "an arc's turns must be 1 to 1000");
      setArc(move, scaled, radius ? std::optional<double>(*radius * (state.inch ? kInch : 1.0)) : std::nullopt, turns, machine, state.plane,
             reader, "G" + std::to_string(move.mode == MotionMode::ArcClockwise ? 2 : 3));
    }
    if (s_->moves == 0 && options.start.empty()) move.from = move.to;
    position = move.to;
    line.move = s_->moves++;
    return &move;
  }
  return nullptr;
}

GcodeProgram parseGcodeProgram(std::string_view text, const std::string& file, const Machine& machine, const GcodeReadOptions& options) {
  GcodeLineReader reader(file, machine, options);
  GcodeProgram program;
  program.file = file;
  const auto lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  program.lines.reserve(lines);
  program.moves.reserve(lines);
  size_t begin = 0;
  while (begin <= text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view raw = text.substr(begin, end - begin);
    begin = end + 1;
    if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    if (end == text.size() && raw.empty()) break;
    GcodeLine& line = program.lines.emplace_back();
    if (const GcodeMove* move = reader.read(raw, line)) program.moves.push_back(*move);
  }
  return program;
}

GcodeProgram readGcodeProgram(const std::string& path, const Machine& machine, const GcodeReadOptions& options) {
  return parseGcodeProgram(readTextFile(path), path, machine, options);
}

std::map<int, double> toolLengthsFromText(const std::string& text, const std::string& key) {
  std::map<int, double> lengths;
  for (const auto& a : parseAssignments(text, key)) lengths[parseCount(a.name, key, 0, 9999)] = parseNumber(a.value, key + " " + a.name);
  return lengths;
}

OptionField toolLengthOption() {
  return {"tool_length", OptionKind::Text, "lengths of the tools named by G43 H<n>, e.g. 1=0,2=35.5 (mm beyond the machine's tool)"};
}

}  // namespace mtacc
