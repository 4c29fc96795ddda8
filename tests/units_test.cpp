#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>

#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

// Every row of the unit table by its value, from the unit's definition (issue 52: a factor of
// nm read as 1e-9 passed every test while only the dimensions of "m" and "rad" were checked).
TEST(Units, EveryUnitByItsValue) {
  const double pi = 3.14159265358979323846;
  const struct {
    const char* text;
    double value;  // mm or rad
    Dimension dimension;
  } rows[] = {
      {"2 nm", 2e-6, Dimension::Length},        {"2 um", 2e-3, Dimension::Length},        {"2 µm", 2e-3, Dimension::Length},
      {"2 mm", 2.0, Dimension::Length},         {"2 cm", 20.0, Dimension::Length},        {"2 m", 2000.0, Dimension::Length},
      {"2 in", 50.8, Dimension::Length},        {"2 rad", 2.0, Dimension::Angle},         {"2 mrad", 2e-3, Dimension::Angle},
      {"2 urad", 2e-6, Dimension::Angle},       {"2 µrad", 2e-6, Dimension::Angle},       {"2 um/m", 2e-6, Dimension::Angle},
      {"2 µm/m", 2e-6, Dimension::Angle},       {"2 mm/m", 2e-3, Dimension::Angle},       {"2 deg", 2 * pi / 180, Dimension::Angle},
      {"2 arcmin", 2 * pi / 10800, Dimension::Angle}, {"2 arcsec", 2 * pi / 648000, Dimension::Angle},
  };
  for (const auto& row : rows) {
    const auto q = parseQuantity(row.text);
    ASSERT_TRUE(q) << row.text;
    EXPECT_NEAR(q->value, row.value, 1e-15 * row.value) << row.text;
    EXPECT_EQ(q->dimension, row.dimension) << row.text;
  }
  // The same count as the message that lists the units: a unit added to the table is added here.
  std::string why;
  parseQuantity("1 furlong", &why);
  const auto listed = why.substr(why.find('('));
  EXPECT_EQ(static_cast<size_t>(std::count(listed.begin(), listed.end(), ' ')) - 1 + 3, std::size(rows)) << listed;  // + µm µrad µm/m
  EXPECT_DOUBLE_EQ(parseQuantity("10µm")->value, 0.01);
  EXPECT_DOUBLE_EQ(parseQuantity("-2.5 mm")->value, -2.5);
}

TEST(Units, RejectsWithAReason) {
  std::string why;
  EXPECT_FALSE(parseQuantity("10", &why));
  EXPECT_NE(why.find("missing unit"), std::string::npos);
  EXPECT_FALSE(parseQuantity("10 furlong", &why));
  EXPECT_NE(why.find("unknown unit"), std::string::npos);
  EXPECT_FALSE(parseQuantity("abc um", &why));
  EXPECT_FALSE(parseQuantity("nan um", &why));
  EXPECT_FALSE(parseQuantity("", &why));
}

}  // namespace
}  // namespace mtacc
