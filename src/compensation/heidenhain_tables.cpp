#include "mtacc/compensation/heidenhain_tables.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

constexpr size_t kComPoints = 256;  // "Compensation value table (.COM) has more than 256 entries" (TNC 407, module 9095)

// A table in the control's fixed-width form: each column as wide as its widest entry, plus one.
std::string table(const std::string& stem, const std::string& extension, const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> widths;
  for (size_t c = 0; c < header.size(); ++c) {
    size_t w = header[c].size();
    for (const auto& row : rows) w = std::max(w, row[c].size());
    widths.push_back(w + 1);
  }
  std::string out = fmt::format("BEGIN {} .{}{}\n", stem, extension, extension == "COM" ? " MM" : "");
  auto line = [&](const std::vector<std::string>& cells) {
    std::string text;
    for (size_t c = 0; c < cells.size(); ++c) text += fmt::format("{:<{}}", cells[c], widths[c]);
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out += text + "\n";
  };
  line(header);
  for (const auto& row : rows) line(row);
  return out + "[END]\n";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> heidenhainTables(const OneAxisReduction& reduction, const std::array<ReversalTrims, 3>& trims) {
  std::vector<std::pair<std::string, std::string>> files;
  std::vector<std::string> cmaHeader{"NR"}, cmaRow{"0"};
  for (int input = 0; input < 3; ++input) {
    std::vector<AxisFunction> outputs;
    for (const auto& f : reduction.functions)
      if (f.input == input) outputs.push_back(f);
    if (outputs.empty()) continue;
    std::sort(outputs.begin(), outputs.end(), [](const AxisFunction& a, const AxisFunction& b) { return a.output < b.output; });
    const std::vector<double> positions = outputs.front().positions;
    if (positions.size() > kComPoints)
      throw InputError({"", 0, "nodes"}, fmt::format("a HEIDENHAIN compensation-value table holds at most {} points, not {}", kComPoints,
                                                     positions.size()));
    // Moving each way: the own column forward, BACKLASH backward.
    const ReversalTrims& reversal = trims[static_cast<size_t>(input)];
    const bool backlash = anyNonZero(reversal.forward) || anyNonZero(reversal.reverse);
    std::vector<double> backward;
    if (backlash) {
      if (reversal.forward.size() != positions.size() || reversal.reverse.size() != positions.size())
        throw InvalidInput("heidenhainTables: the reversal trims are not at the functions' points");
      auto own = std::find_if(outputs.begin(), outputs.end(), [&](const AxisFunction& f) { return f.output == input; });
      if (own == outputs.end()) {
        outputs.push_back({input, input, positions, std::vector<double>(positions.size(), 0.0), 0.0});
        std::sort(outputs.begin(), outputs.end(), [](const AxisFunction& a, const AxisFunction& b) { return a.output < b.output; });
        own = std::find_if(outputs.begin(), outputs.end(), [&](const AxisFunction& f) { return f.output == input; });
      }
      for (size_t n = 0; n < positions.size(); ++n) {
        backward.push_back(own->values[n] + reversal.reverse[n]);
        own->values[n] += reversal.forward[n];
      }
    }
    std::vector<std::string> header{"NR", "AXISPOS"};
    for (const auto& f : outputs) header.emplace_back(kLinearAxisNames[f.output]);
    if (backlash) header.emplace_back("BACKLASH");
    std::vector<std::vector<std::string>> rows;
    for (size_t n = 0; n < positions.size(); ++n) {
      std::vector<std::string> row{std::to_string(n), fmt::format("{:+.4f}", positions[n])};
      for (const auto& f : outputs) row.push_back(fmt::format("{:+.5f}", f.values[n]));
      if (backlash) row.push_back(fmt::format("{:+.5f}", backward[n]));
      rows.push_back(std::move(row));
    }
    const std::string stem = fmt::format("heidenhain-{}", kLinearAxisNames[input]), file = stem + ".com";
    files.emplace_back(file, table(stem, "COM", header, rows));
    cmaHeader.emplace_back(kLinearAxisNames[input]);
    cmaRow.push_back(file);
  }
  cmaHeader.emplace_back("ACTIVE");
  cmaRow.emplace_back("*");
  files.emplace_back("heidenhain.cma", table("heidenhain", "CMA", cmaHeader, {cmaRow}));
  return files;
}

}  // namespace mtacc
