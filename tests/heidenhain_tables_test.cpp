// HEIDENHAIN compensation-value tables (issue 17, item 3): the *.COM files and the *.CMA
// assignment read back as the control's tables (BEGIN line, column header, rows numbered in NR,
// [END]), the columns those of the MANUALplus 620 technical manual (AXISPOS, one column per
// dependent axis; the CMA's axis columns and ACTIVE), the limit of 256 points, and the correction
// they give, interpolated as the control does, equal to the one-axis functions'.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "mtacc/compensation/heidenhain_tables.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct ReadTable {
  std::string stem, extension;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

ReadTable readTable(const std::string& text) {
  ReadTable t;
  std::istringstream in(text);
  std::string line;
  std::smatch m;
  std::getline(in, line);
  EXPECT_TRUE(std::regex_match(line, m, std::regex(R"(BEGIN (\S+) \.(COM MM|CMA))"))) << line;
  t.stem = m[1];
  t.extension = m[2].str().substr(0, 3);
  bool ended = false;
  while (std::getline(in, line)) {
    EXPECT_FALSE(ended) << "after [END]: " << line;
    if (line == "[END]") {
      ended = true;
      continue;
    }
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string s; words >> s;) w.push_back(s);
    if (t.header.empty()) t.header = w;
    else t.rows.push_back(w);
  }
  EXPECT_TRUE(ended);
  return t;
}

// Linear between the compensation points, the end values beyond them.
double interpolate(const std::vector<double>& at, const std::vector<double>& values, double x) {
  if (x <= at.front()) return values.front();
  if (x >= at.back()) return values.back();
  const size_t k = static_cast<size_t>(std::upper_bound(at.begin(), at.end(), x) - at.begin()) - 1;
  const double u = (x - at[k]) / (at[k + 1] - at[k]);
  return (1 - u) * values[k] + u * values[k + 1];
}

TEST(HeidenhainTables, ReadBackAndInterpolateToTheOneAxisFunctions) {
  const auto setup = loadMachineSetup({"three-axis-vertical", "", "", std::nullopt, ""});
  const CorrectionGrid grid = correctionGrid(setup.machine, setup.errors, {{11, 9, 7}, {}});
  const OneAxisReduction reduction = reduceToOneAxisFunctions(grid, 9);
  const auto files = heidenhainTables(reduction);
  ASSERT_EQ(files.size(), 4u);
  // Per input axis, the functions it drives: AXISPOS and the column of each output axis.
  std::map<std::string, std::pair<std::vector<double>, std::map<std::string, std::vector<double>>>> com;
  for (const auto& [name, text] : files) {
    const ReadTable t = readTable(text);
    if (name == "heidenhain.cma") {
      EXPECT_EQ(t.extension, "CMA");
      EXPECT_EQ(t.header, (std::vector<std::string>{"NR", "X", "Y", "Z", "ACTIVE"}));
      ASSERT_EQ(t.rows.size(), 1u);
      EXPECT_EQ(t.rows[0], (std::vector<std::string>{"0", "heidenhain-X.com", "heidenhain-Y.com", "heidenhain-Z.com", "*"}));
      continue;
    }
    EXPECT_EQ(t.extension, "COM");
    EXPECT_EQ(t.stem + ".com", name);
    ASSERT_GE(t.header.size(), 3u);
    EXPECT_EQ(t.header[0], "NR");
    EXPECT_EQ(t.header[1], "AXISPOS");
    auto& [positions, columns] = com[name.substr(11, 1)];
    for (size_t r = 0; r < t.rows.size(); ++r) {
      ASSERT_EQ(t.rows[r].size(), t.header.size());
      EXPECT_EQ(t.rows[r][0], std::to_string(r));
      positions.push_back(std::stod(t.rows[r][1]));
      for (size_t c = 2; c < t.header.size(); ++c) columns[t.header[c]].push_back(std::stod(t.rows[r][c]));
    }
  }
  size_t functions = 0;
  for (const auto& [input, table] : com) functions += table.second.size();
  EXPECT_EQ(functions, reduction.functions.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 1.1);  // beyond the ends too
  const char* names[3] = {"X", "Y", "Z"};
  for (int k = 0; k < 500; ++k) {
    Vec3 xyz;
    for (int a = 0; a < 3; ++a) xyz[a] = grid.start[static_cast<size_t>(a)] + u(rng) * grid.step[static_cast<size_t>(a)] * (grid.counts[static_cast<size_t>(a)] - 1);
    Vec3 fromFiles = Vec3::Zero();
    for (int input = 0; input < 3; ++input) {
      const auto& [positions, columns] = com.at(names[input]);
      for (const auto& [output, values] : columns) fromFiles[output[0] - 'X'] += interpolate(positions, values, xyz[input]);
    }
    // 5 decimals of the values (5 nm each, three tables at most per axis); 4 of the positions.
    EXPECT_LE((fromFiles - reduction.correction(xyz)).cwiseAbs().maxCoeff(), 2e-5) << k;
  }
}

TEST(HeidenhainTables, AtMost256PointsPerTable) {
  const auto setup = loadMachineSetup({"three-axis-vertical", "", "", std::nullopt, ""});
  const OneAxisReduction reduction = reduceToOneAxisFunctions(correctionGrid(setup.machine, setup.errors, {{257, 2, 2}, {}}), 9);
  const auto e = test::thrown<InputError>([&] { heidenhainTables(reduction); });
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->reason(), "a HEIDENHAIN compensation-value table holds at most 256 points, not 257");
}

}  // namespace
}  // namespace mtacc
