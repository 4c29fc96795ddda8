#include <gtest/gtest.h>

#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

TEST(Units, LengthsInMillimetres) {
  EXPECT_DOUBLE_EQ(parseQuantity("10 um")->value, 0.01);
  EXPECT_DOUBLE_EQ(parseQuantity("10µm")->value, 0.01);
  EXPECT_DOUBLE_EQ(parseQuantity("-2.5 mm")->value, -2.5);
  EXPECT_DOUBLE_EQ(parseQuantity("1 in")->value, 25.4);
  EXPECT_EQ(parseQuantity("3 m")->dimension, Dimension::Length);
}

TEST(Units, AnglesInRadians) {
  EXPECT_DOUBLE_EQ(parseQuantity("30 urad")->value, 30e-6);
  EXPECT_DOUBLE_EQ(parseQuantity("30 um/m")->value, 30e-6);
  EXPECT_DOUBLE_EQ(parseQuantity("5 arcsec")->value, 5 * kPi / 648000);
  EXPECT_DOUBLE_EQ(parseQuantity("0.01 deg")->value, 0.01 * kPi / 180);
  EXPECT_EQ(parseQuantity("1 rad")->dimension, Dimension::Angle);
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
