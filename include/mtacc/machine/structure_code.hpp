#pragma once
// Structure codes (ISO 10791 working practice, seed 000 §3.3.1): the axes from tool to
// workpiece through the bed, e.g. "t-(C)-Z-Y-b-X-B-C-w". The workpiece-first forms of
// seeds 002 ("w-C'bZYXB(C1)-t") and 004 ("WCAYFXZT", F = frame) are accepted too.
#include <optional>
#include <string>
#include <vector>

namespace mtacc {

struct StructureCode {
  std::string text;
  std::vector<std::string> toolChain;       // commanded axes from the bed to the tool
  std::vector<std::string> workpieceChain;  // commanded axes from the bed to the workpiece
  std::optional<std::string> spindle;       // the tool spindle, written in parentheses

  // Canonical tool-first form, e.g. "t-(C)-Z-Y-b-X-B-C-w".
  std::string toolFirst() const;
};

// Throws InvalidInput with a reason when the code cannot be read.
StructureCode parseStructureCode(const std::string& text);

}  // namespace mtacc
