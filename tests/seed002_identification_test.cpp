// Seed 002 §5.4: the numerical experiment. Table 6 (L1635-1748) eccentricities through the
// closed-form identification Eqs 17-28 give Table 7's "identified" column (L1749-1838).
// Reference seed002_ballbar_multitasking.md §12.2: exact to the printed digits, so the
// tolerance is half a unit of the last printed digit (0.005 um, 0.005 arcsec).
#include <gtest/gtest.h>

#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/procedures/ballbar_seed002.hpp"
#include "reference_values.hpp"

namespace mtacc {
namespace {

TEST(Seed002Identification, Table7FromTable6ThroughEqs17To28) {
  const double um = 1e-3;
  Seed002Eccentricities e{};
  e.bxEx = 16.63 * um, e.bxEz = -4.02 * um;
  e.byEx = -11.24 * um, e.byEz = 10.05 * um;
  e.caEx = 0.29 * um, e.caEy = 0.05 * um;
  e.crEx = 25.73 * um, e.crEy = -19.59 * um;
  e.cr1Ex = 26.89 * um, e.cr1Ey = -20.00 * um;
  e.cr2Ex = 28.97 * um, e.cr2Ey = -23.26 * um;
  const Seed002Setup s{360.0, 410.0, 50.0, 300.0, 340.0};  // L570 and the footnotes of Table 6
  const auto d = identifySeed002(e, s);
  const double as = 1.0 / kArcsec;
  struct Entry {
    int line;
    const char* name;
    double computed, printed;
    const char* unit;
  };
  const Entry entries[] = {{1758, "dxBT", d.dxBT / um, 10.96, "um"},      {1765, "dzBT", d.dzBT / um, 16.63, "um"},
                           {1772, "alphaBT", d.alphaBT * as, 7.69, "arcsec"}, {1779, "alphaXB", d.alphaXB * as, 3.44, "arcsec"},
                           {1786, "betaXB", d.betaXB * as, 3.80, "arcsec"},   {1793, "gammaXB", d.gammaXB * as, 6.44, "arcsec"},
                           {1800, "alphaYZ", d.alphaYZ * as, 2.32, "arcsec"}, {1807, "betaYZ", d.betaYZ * as, 4.79, "arcsec"},
                           {1814, "dxCZ", d.dxCZ / um, 13.01, "um"},          {1821, "dyCZ", d.dyCZ / um, 6.96, "um"},
                           {1828, "alphaCZ", d.alphaCZ * as, 2.11, "arcsec"}, {1835, "betaCZ", d.betaCZ * as, 5.98, "arcsec"}};
  for (const auto& e : entries)
    test::expectReproduced({"002", "Table 7, L" + std::to_string(e.line), std::string(e.name) + " identified from Table 6", e.printed, 2,
                            e.unit},
                           e.computed, 0.005, "half the printed digit");
}

TEST(Seed002Identification, UnseparableSetupIsRefused) {
  const Seed002Eccentricities e{};
  EXPECT_THROW(identifySeed002(e, Seed002Setup{360, 360, 50, 300, 340}), InvalidInput);
  EXPECT_THROW(identifySeed002(e, Seed002Setup{360, 410, 50, 300, 300}), InvalidInput);
}

}  // namespace
}  // namespace mtacc
