// Seed 002 §5.4: the numerical experiment. Table 6 (L1635-1748) eccentricities, bundled as
// data/ballbar/seed002-table6.yaml, through `mtacc multitasking`'s workflow (the closed-form
// identification Eqs 17-28) give Table 7's "identified" column (L1749-1838).
// Reference seed002_ballbar_multitasking.md §12.2: exact to the printed digits, so the
// tolerance is half a unit of the last printed digit (0.005 um, 0.005 arcsec).
#include <gtest/gtest.h>

#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/procedures/ballbar_seed002.hpp"
#include "mtacc/workflows/multitasking_identification.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(Seed002Identification, Table7FromTable6ThroughEqs17To28) {
  const double um = 1e-3;
  // Table 6 and its set-up as bundled (data/ballbar/seed002-table6.yaml), through the workflow of
  // `mtacc multitasking`.
  const auto d = identifyMultitasking({{"data", {bundledDataDir() + "/ballbar/seed002-table6.yaml"}}}).deviations;
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

// The errors file it writes reads back on the bundled machine of this kind as the ISO errors of
// the alias table (docs/conventions.md): dxBT is X0C1; the squareness alphaYZ turns the Y axis
// and, with it, the B head (A0Y and A0B each take it), on top of the head's own alphaXB (A0B).
TEST(Seed002Identification, ErrorsFileOfTheTwelveReadsBackOnTheMachine) {
  test::TestFolder folder("multitasking");
  const std::string out = (folder.dir() / "errors.yaml").string();
  const auto r = identifyMultitasking({{"data", {bundledDataDir() + "/ballbar/seed002-table6.yaml"}}}, out);
  const auto machine = test::bundled("multitasking-b-c");
  const auto errors = loadErrors(*machine, out);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "X0C1")), r.deviations.dxBT, 1e-15);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "A0Y")), r.deviations.alphaYZ, 1e-18);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "A0B")), r.deviations.alphaXB + r.deviations.alphaYZ, 1e-18);
  EXPECT_NEAR(parameterValue(errors, findParameter(*machine, errors, "B0C")), r.deviations.betaCZ, 1e-18);
}

TEST(Seed002Identification, UnseparableSetupIsRefused) {
  const Seed002Eccentricities e{};
  EXPECT_THROW(identifySeed002(e, Seed002Setup{360, 360, 50, 300, 340}), InvalidInput);
  EXPECT_THROW(identifySeed002(e, Seed002Setup{360, 410, 50, 300, 300}), InvalidInput);
}

}  // namespace
}  // namespace mtacc
