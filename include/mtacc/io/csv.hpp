#pragma once
// Reading the documented CSV inputs (docs/file-formats.md): a header row of column names,
// then rows of plain numbers. '#' starts a comment line.
#include <string>
#include <vector>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct CsvTable {
  std::string file;
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  // source line of each row
  int headerLine = 1;
};

// Throws InputError naming file, line and column for a wrong column count, a value that is
// not a finite number, or an empty table.
CsvTable readCsv(const std::string& path);
CsvTable parseCsv(const std::string& text, const std::string& sourceName);

// Axis positions from a table with one column per commanded axis (linear mm, rotary deg) and
// optional "<axis>_dir" columns (+1, -1, 0) for the direction of motion.
struct PoseTable {
  JointMatrix q;            // mm, rad
  DirectionMatrix direction;  // empty when no direction column was given
};
// Any other column is an error unless named in `otherColumns`.
PoseTable posesFromCsv(const Machine& machine, const CsvTable& table, const std::vector<std::string>& otherColumns = {});

// Looks up the required columns by name; throws InputError when one is missing.
std::vector<int> requireColumns(const CsvTable& table, const std::vector<std::string>& names);

}  // namespace mtacc
