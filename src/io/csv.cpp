#include "mtacc/io/csv.hpp"

#include "mtacc/core/text_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {

CsvTable parseCsv(const std::string& text, const std::string& sourceName) {
  CsvTable t;
  t.file = sourceName;
  std::stringstream in(text);
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    auto cells = splitFields(s);
    if (t.header.empty()) {
      std::set<std::string> seen;
      for (const auto& name : cells)
        if (!seen.insert(name).second) throw InputError(InputLocation{sourceName, lineNo, name}, "column given twice");
      t.header = cells;
      t.headerLine = lineNo;
      continue;
    }
    if (cells.size() != t.header.size())
      throw InputError(InputLocation{sourceName, lineNo, ""},
                       "expected " + std::to_string(t.header.size()) + " columns, found " + std::to_string(cells.size()));
    std::vector<double> row;
    for (size_t c = 0; c < cells.size(); ++c) {
      double v = 0;
      const auto& cell = cells[c];
      const auto res = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (res.ec != std::errc() || res.ptr != cell.data() + cell.size() || !std::isfinite(v))
        throw InputError(InputLocation{sourceName, lineNo, t.header[c]}, "not a finite number: '" + cell + "'");
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
    t.lines.push_back(lineNo);
  }
  if (t.header.empty() || t.rows.empty()) throw InputError(InputLocation{sourceName, lineNo, ""}, "no data rows");
  return t;
}

CsvTable readCsv(const std::string& path) {
  return parseCsv(readTextFile(path), path);
}

std::vector<int> requireColumns(const CsvTable& t, const std::vector<std::string>& names) {
  std::vector<int> idx;
  for (const auto& n : names) {
    int found = -1;
    for (size_t c = 0; c < t.header.size(); ++c)
      if (t.header[c] == n) found = static_cast<int>(c);
    if (found < 0) throw InputError(InputLocation{t.file, t.headerLine, n}, "missing column '" + n + "'");
    idx.push_back(found);
  }
  return idx;
}

PoseTable posesFromCsv(const Machine& m, const CsvTable& t, const std::vector<std::string>& otherColumns) {
  const auto names = m.commandedAxisNames();
  const auto cols = requireColumns(t, names);
  for (size_t c = 0; c < t.header.size(); ++c) {
    const auto& h = t.header[c];
    const bool known = std::find(names.begin(), names.end(), h) != names.end() ||
                       std::find(otherColumns.begin(), otherColumns.end(), h) != otherColumns.end() ||
                       (h.size() > 4 && h.compare(h.size() - 4, 4, "_dir") == 0 &&
                        std::find(names.begin(), names.end(), h.substr(0, h.size() - 4)) != names.end());
    if (!known) throw InputError(InputLocation{t.file, t.headerLine, h}, "unknown column '" + h + "' (axis names, <axis>_dir" +
                                                                (otherColumns.empty() ? std::string(")") : ", readings)"));
  }
  PoseTable p;
  const long n = static_cast<long>(t.rows.size());
  p.q.resize(n, static_cast<long>(names.size()));
  std::vector<int> dirCols(names.size(), -1);
  bool anyDir = false;
  for (size_t a = 0; a < names.size(); ++a)
    for (size_t c = 0; c < t.header.size(); ++c)
      if (t.header[c] == names[a] + "_dir") {
        dirCols[a] = static_cast<int>(c);
        anyDir = true;
      }
  if (anyDir) p.direction = DirectionMatrix::Zero(n, static_cast<long>(names.size()));
  for (long r = 0; r < n; ++r) {
    for (size_t a = 0; a < names.size(); ++a) {
      const double v = t.rows[static_cast<size_t>(r)][static_cast<size_t>(cols[a])];
      p.q(r, static_cast<long>(a)) = v * m.axes[a].fileUnit();
      if (dirCols[a] >= 0) {
        const double d = t.rows[static_cast<size_t>(r)][static_cast<size_t>(dirCols[a])];
        if (d != -1 && d != 0 && d != 1)
          throw InputError(InputLocation{t.file, t.lines[static_cast<size_t>(r)], names[a] + "_dir"}, "direction must be -1, 0 or 1");
        p.direction(r, static_cast<long>(a)) = static_cast<int>(d);
      }
    }
    const std::vector<double> pose(p.q.row(r).data(), p.q.row(r).data() + p.q.cols());
    if (const auto violation = m.travelViolation(pose); !violation.empty())
      throw InputError(InputLocation{t.file, t.lines[static_cast<size_t>(r)], ""}, "pose " + violation);
  }
  return p;
}

}  // namespace mtacc
