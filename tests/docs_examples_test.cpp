// docs/examples/README.md: the example machines' poses with the numbers worked out by hand in
// the page, checked against the forward kinematics (issue 20: a new user writes these machines
// from the docs alone).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::istringstream in(row.substr(1));
  for (std::string cell; std::getline(in, cell, '|');) {
    const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    out.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return out;
}

Vec3 vector3(const std::string& text) {
  std::istringstream in(text);
  Vec3 v;
  in >> v.x() >> v.y() >> v.z();
  EXPECT_TRUE(in) << text;
  return v;
}

TEST(DocsExamples, ForwardKinematicsAsWorkedOut) {
  const std::string folder = std::string(MTACC_TEST_DATA) + "/../../docs/examples/";
  std::ifstream page(folder + "README.md");
  ASSERT_TRUE(page) << folder;
  int rows = 0;
  for (std::string line; std::getline(page, line);) {
    if (!line.starts_with("| ")) continue;
    const auto c = cells(line);
    if (c.size() != 4 || !c[0].ends_with(".yaml")) continue;
    const auto machine = std::make_shared<const Machine>(loadMachine(folder + c[0]));
    const std::vector<double> q = parsePose(*machine, c[1], "pose");
    const ToolPoint tool = toolPoint(compileNominal(machine), q.data());
    EXPECT_LE((tool.position - vector3(c[2])).norm(), 1e-9) << line << "\n  mtacc: " << tool.position.transpose();
    EXPECT_LE((tool.direction - vector3(c[3])).norm(), 1e-12) << line << "\n  mtacc: " << tool.direction.transpose();
    ++rows;
  }
  EXPECT_EQ(rows, 5);
}

}  // namespace
}  // namespace mtacc
