#pragma once
// NC programs in axis positions (G-code, RS-274 / ISO 6983 as LinuxCNC, Fanuc and Siemens read
// it): G0/G1/G2/G3 in the planes G17/G18/G19, G90/G91, G20/G21, F, G43 H/G49 tool lengths and
// rotary words on G0/G1. Every axis word is an axis position of the machine (mm, or inch under
// G20; deg for rotary axes), with the machine file's zero as the zero of G54. Words that do not
// move the machine (M, S, T, N, G4 P, G40, G54, G61, G64, G80, G94, comments) are kept for the
// writer; anything else is refused with its file and line (never dropped).
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/compensation/nc_program.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct GcodeReadOptions {
  // Axis positions before the first move; empty: unknown, the first move starts at its end (an
  // approach, its path not judged) and the axes it does not name at zero.
  std::vector<double> start;
  std::map<int, double> toolLengths;    // G43 H<n>: tool n's length in mm (see GcodeMove::toolLength)
};

// A program read a line at a time, the modal state (motion, plane, units, distance mode, feed,
// tool length) and the axes' positions carried from line to line: a program of any length in
// bounded memory. Throws InputError naming file, line and word.
class GcodeLineReader {
 public:
  GcodeLineReader(const std::string& file, const Machine& machine, const GcodeReadOptions& options = {});
  GcodeLineReader(GcodeLineReader&&) noexcept;
  ~GcodeLineReader();
  // The next line's text (without its newline) into `line` (its number, kept words, N word and
  // its move's index, or -1); its move, valid until the next call, or nullptr.
  const GcodeMove* read(std::string_view text, GcodeLine& line);
  int lines() const;  // read so far
  int moves() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// The same over a whole text. Throws InputError naming file, line and word. The machine's
// commanded axes must be named by single letters (their G-code addresses).
GcodeProgram parseGcodeProgram(std::string_view text, const std::string& file, const Machine& machine,
                               const GcodeReadOptions& options = {});
GcodeProgram readGcodeProgram(const std::string& path, const Machine& machine, const GcodeReadOptions& options = {});

// "1=0,2=35.5": the lengths (mm beyond the machine file's tool) of the tools G43 H<n> names.
// Throws InputError naming `key` for a tool number outside 0..9999 or a length not a number.
std::map<int, double> toolLengthsFromText(const std::string& text, const std::string& key);
// The option `tool_length` of the workflows that read a program, read by toolLengthsFromText.
OptionField toolLengthOption();

}  // namespace mtacc
