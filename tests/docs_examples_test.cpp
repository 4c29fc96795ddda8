// docs/examples/README.md: the example machines' poses with the numbers worked out by hand in
// the page, checked against the forward kinematics (issue 20: a new user writes these machines
// from the docs alone).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "test_paths.hpp"

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

const std::string kFolder = test::testDataDir() + "/../../docs/examples/";

// The table rows of the page with `columns` cells whose first names a machine file.
std::vector<std::vector<std::string>> machineRows(size_t columns) {
  std::ifstream page(kFolder + "README.md");
  EXPECT_TRUE(page) << kFolder;
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(page, line);) {
    if (!line.starts_with("| ")) continue;
    auto c = cells(line);
    if (c.size() == columns && c[0].ends_with(".yaml")) rows.push_back(std::move(c));
  }
  return rows;
}

TEST(DocsExamples, ForwardKinematicsAsWorkedOut) {
  int rows = 0;
  for (const auto& c : machineRows(4)) {
    const std::string line = c[0] + " | " + c[1];
    const auto machine = std::make_shared<const Machine>(loadMachine(kFolder + c[0]));
    const std::vector<double> q = parsePose(*machine, c[1], "pose");
    const ToolPoint tool = toolPoint(compileNominal(machine), q.data());
    EXPECT_LE((tool.position - vector3(c[2])).norm(), 1e-9) << line << "\n  mtacc: " << tool.position.transpose();
    EXPECT_LE((tool.direction - vector3(c[3])).norm(), 1e-12) << line << "\n  mtacc: " << tool.direction.transpose();
    ++rows;
  }
  EXPECT_EQ(rows, 10);
}

// One error alone, "B.zero = 10 urad", against the nominal machine at the pose: the TCP error
// in um and the change of the tool direction in urad, to 1e-4 (the page's second-order terms,
// 250 mm x (10 urad)^2, are 2.5e-5 um).
TEST(DocsExamples, LocationErrorsAsWorkedOut) {
  int rows = 0;
  for (const auto& c : machineRows(5)) {
    const std::string line = c[0] + " | " + c[1] + " | " + c[2];
    const auto machine = std::make_shared<const Machine>(loadMachine(kFolder + c[0]));
    const auto equals = c[1].find('=');
    ASSERT_NE(equals, std::string::npos) << line;
    const std::string name = c[1].substr(0, c[1].find_last_not_of(' ', equals - 1) + 1);
    ErrorModel errors = ErrorModel::zero(*machine);
    const Parameter p = findParameter(*machine, errors, name);
    setParameterValue(errors, p, parseQuantityAs(c[1].substr(equals + 1), p.dimension, name));
    const std::vector<double> q = parsePose(*machine, c[2], "pose");
    const ToolPoint actual = toolPoint(compile(machine, errors), q.data());
    const ToolPoint nominal = toolPoint(compileNominal(machine), q.data());
    const Vec3 tcpError = (actual.position - nominal.position) * 1e3, turn = (actual.direction - nominal.direction) * 1e6;
    EXPECT_LE((tcpError - vector3(c[3])).norm(), 1e-4) << line << "\n  mtacc: " << tcpError.transpose();
    EXPECT_LE((turn - vector3(c[4])).norm(), 1e-4) << line << "\n  mtacc: " << turn.transpose();
    ++rows;
  }
  EXPECT_EQ(rows, 5);
}

}  // namespace
}  // namespace mtacc
