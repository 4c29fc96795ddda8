// Seed 000 ch. 7 (reference seed000_part2_rigid_body_dynamics.md §3.2): the two bundled
// t-Z-Y-X-b-w designs. The thesis gives no parameters, so the checks are its qualitative
// statements about Table 7.1 (L6082-6103) and the position sweep of Fig. 7.7 (L6213-6286),
// and a guard on the bundled models' dominant modes (not a thesis number).
#include <gtest/gtest.h>

#include "mtacc/io/structure_yaml.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"

namespace mtacc {
namespace {

// Position 1: Y and Z extended (Y at +travel, Z at -travel), X centred (L6062).
const std::vector<double> kPosition1 = {0.0, 0.4, -0.3};

Eigen::MatrixXd table71(const std::string& name) {
  const auto m = loadStructure(name);
  return (accelerationResponse(assembleStructure(m, kPosition1)) * kStandardGravity * 1e6).cwiseAbs();
}

// Not a reproduction: the bundled models' parameters were chosen so that the dominant mode
// falls in the 50-120 Hz of chapter 6's four-body model, and the 106 / 105 Hz are mtacc's own
// outputs, so this only guards the bundled models against an accidental change. The thesis'
// definition used: "dominant frequency = frequency of a maximum in a spectral density curve"
// (L5064-5084), the largest peak of |Hxx| over 0-200 Hz at position 1.
TEST(BundledArmModels, DominantModeStaysInTheChosenRange) {
  std::vector<double> f;
  for (int i = 1; i <= 200; ++i) f.push_back(i);
  for (const char* name : {"tzyx-arm-x", "tzyx-arm-y"}) {
    const auto m = loadStructure(name);
    const auto mats = assembleStructure(m, kPosition1);
    const auto h = frfModal(mats, undampedModes(m, mats), f);
    size_t peak = 0;
    for (size_t i = 0; i < h.size(); ++i)
      if (std::abs(h[i](0, 0)) > std::abs(h[peak](0, 0))) peak = i;
    SCOPED_TRACE(name);
    EXPECT_GE(f[peak], 50.0);
    EXPECT_LE(f[peak], 120.0);
  }
}

TEST(Seed000Dynamics, Table7_1QualitativeRelations) {
  const auto orig = table71("tzyx-arm-x"), alt = table71("tzyx-arm-y");
  // Hx/x'' is the largest entry of both and larger for the alternative (L6106-6120).
  EXPECT_EQ(orig.maxCoeff(), orig(0, 0));
  EXPECT_EQ(alt.maxCoeff(), alt(0, 0));
  EXPECT_GT(alt(0, 0), orig(0, 0));
  // Hy/x'': the alternative's arm yaws (L5971-5975); Hx/y'': one-sided drive of the whole arm.
  EXPECT_GT(alt(1, 0), orig(1, 0));
  EXPECT_GT(alt(0, 1), 10 * std::max(orig(0, 1), 1e-3));
  // Hy/y'' and Hz/y'' larger for the alternative (larger moved mass, L6160-6175).
  EXPECT_GT(alt(1, 1), orig(1, 1));
  EXPECT_GT(alt(2, 1), orig(2, 1));
}

TEST(Seed000Dynamics, Figure7_7OriginalBetterAtMostPositions) {
  const auto orig = loadStructure("tzyx-arm-x"), alt = loadStructure("tzyx-arm-y");
  const auto mo = dynamicsMap(orig, {"Y", "Z", 20, 20, {}}, dynamicsQuantity(orig, "Hx/X"));
  const auto ma = dynamicsMap(alt, {"Y", "Z", 20, 20, {}}, dynamicsQuantity(alt, "Hx/X"));
  // Position 1 is the worst case of the original; the original's upper quartile lies below
  // the alternative's lower quartile; the alternative spreads more; its best value beats the
  // original's median (L6252-6286).
  EXPECT_NEAR(mo.statistics.max, mo.values(19, 0), 1e-9);
  EXPECT_LT(mo.statistics.upperQuartile, ma.statistics.lowerQuartile);
  EXPECT_GT(ma.statistics.upperQuartile - ma.statistics.lowerQuartile,
            mo.statistics.upperQuartile - mo.statistics.lowerQuartile);
  EXPECT_LT(ma.statistics.min, mo.statistics.median);
}

}  // namespace
}  // namespace mtacc
