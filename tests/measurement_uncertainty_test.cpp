// ISO/TR 230-9 uncertainty of the ISO 230-2 values, tolerances and the ISO 14253-1 verdict. No
// worked example of a laser positioning budget with all its inputs was found in public sources
// (ISO 230-2:2014 annex A and ISO/TR 230-9 are not public), so each contributor is checked against
// its closed form, and the refractive index of air, which the wavelength contributors differentiate,
// against NIST's independent shop-floor formula and the IAPWS steam-table values.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/acceptance_yaml.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/measurement_conditions_yaml.hpp"
#include "mtacc/io/tolerances_yaml.hpp"
#include "mtacc/procedures/air_refractive_index.hpp"
#include "mtacc/procedures/measurement_uncertainty.hpp"
#include "mtacc/workflows/positioning.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

// NIST Engineering Metrology Toolbox, "Index of Refraction of Air", App. B: the simple shop-floor
// formula, p in kPa, t in C, RH in %.
double shopFloorIndex(double t, double pKPa, double rh) { return 1 + 7.86e-4 * pKPa / (273 + t) - 1.5e-11 * rh * (t * t + 160); }

TEST(AirRefractiveIndex, AgreesWithNistShopFloorFormulaOverItsRange) {
  // The shop-floor formula is a three-term fit of the full equation: they differ by up to 1.02e-7
  // (at 10 C, 60 kPa, saturated air). 1.5e-7 (0.15 ppm) holds over the whole range; a coefficient
  // wrong in its third digit (3e-7 and more) does not.
  for (const double t : {0.0, 10.0, 20.0, 30.0, 40.0})
    for (const double p : {60e3, 90e3, 101325.0, 120e3})
      for (const double rh : {0.0, 50.0, 100.0})
        EXPECT_NEAR(airRefractiveIndex({t, p, rh}), shopFloorIndex(t, p / 1e3, rh), 1.5e-7) << t << " C " << p << " Pa " << rh << " %";
}

TEST(AirRefractiveIndex, SensitivitiesMatchTheShopFloorFormulasDerivatives) {
  // At 20.6 C, 1001 hPa, 45 %: dn/dt = -7.86e-4 p / (273 + t)^2 - 3e-11 RH t, dn/dp = 7.86e-4 / (273 + t)
  // per kPa, dn/dRH = -1.5e-11 (t^2 + 160). The fit's derivatives agree to about 1 % (3 % for the
  // humidity term, whose fit is the coarsest).
  const double t = 20.6, p = 100.1, rh = 45;
  const auto d = airRefractiveIndexSensitivities({t, p * 1e3, rh});
  EXPECT_NEAR(d.perKelvin / (-7.86e-4 * p / std::pow(273 + t, 2) - 3e-11 * rh * t), 1, 0.01);
  EXPECT_NEAR(d.perPascal / (7.86e-4 / (273 + t) / 1e3), 1, 0.01);
  EXPECT_NEAR(d.perPercent / (-1.5e-11 * (t * t + 160)), 1, 0.03);
  EXPECT_LT(d.perKelvin, 0);  // warmer air, a shorter index: the readings grow
}

TEST(AirRefractiveIndex, SaturationVapourPressureMatchesTheSteamTables) {
  // IAPWS-IF97: 611.657 Pa at the triple point (273.16 K); the steam tables' 2.3392 kPa at 20 C.
  EXPECT_NEAR(saturationVapourPressure(0.01), 611.657, 0.01);
  EXPECT_NEAR(saturationVapourPressure(20), 2339.2, 0.1);
}

TEST(AirRefractiveIndex, RefusesConditionsOutsideTheEquationsRange) {
  EXPECT_THROW(airRefractiveIndex({45, 101325, 50}), InvalidInput);
  EXPECT_THROW(airRefractiveIndex({20, 50e3, 50}), InvalidInput);
  EXPECT_THROW(airRefractiveIndex({20, 101325, 101}), InvalidInput);
  EXPECT_THROW(airRefractiveIndex({20, 101325, 50}, 200), InvalidInput);
  EXPECT_NO_THROW(airRefractiveIndexSensitivities({40, 120e3, 100}));  // the range's corner
}

// Five targets over 800 mm, five cycles; every target's readings 0, 1, 2, 3, 4 um plus an offset,
// so that s = sqrt(2.5) um everywhere.
PositioningTest eightHundredMillimetres() {
  PositioningTest t;
  t.targets = {0, 200, 400, 600, 800};
  t.forward.resize(5, 5);
  t.backward.resize(5, 5);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      t.forward(i, j) = (j + 2.0 * i) * kMicro;
      t.backward(i, j) = (j - 1.0 + 1.5 * i) * kMicro;
    }
  return t;
}

MeasurementConditions laserConditions() {
  return parseMeasurementConditions(R"(
instrument: laser interferometer
calibration: 0.4 ppm + 0.1 um
air_temperature: 20.6 C ± 0.2 K
air_pressure: 1001 hPa ± 1 hPa
air_humidity: 45 % ± 6 %
air_change: 0.4 K, 1.5 hPa
dead_path: 120 mm
machine_temperature: 21.4 C ± 0.2 K
expansion: 11.5 ppm/K ± 2 ppm/K
misalignment: 0.5 mm
drift: 1.2 um
)",
                                    "laser.yaml");
}

double contributor(const UncertaintyBudget& b, const std::string& symbol) {
  for (const auto& k : b.contributors)
    if (k.symbol == symbol) return k.standard;
  ADD_FAILURE() << "no contributor " << symbol;
  return NAN;
}

TEST(PositioningUncertainty, EachContributorIsItsClosedForm) {
  const auto test = eightHundredMillimetres();
  const auto result = evaluatePositioning(test);
  const auto c = laserConditions();
  EXPECT_EQ(c.defaulted, std::vector<std::string>{"wavelength"});
  const auto b = positioningUncertainty(test, result, c);
  const double L = 800, r3 = std::sqrt(3.0);
  EXPECT_DOUBLE_EQ(b.measuredLength, L);
  EXPECT_NEAR(contributor(b, "u_DEVICE"), 0.4e-6 * L / 2, 1e-15);
  EXPECT_NEAR(contributor(b, "u_DEVICE,0"), 0.1e-3 / 2, 1e-15);
  const auto d = airRefractiveIndexSensitivities({20.6, 100100, 45});
  EXPECT_NEAR(contributor(b, "u_λ,T"), std::abs(d.perKelvin) * 0.2 / r3 * L, 1e-15);
  EXPECT_NEAR(contributor(b, "u_λ,p"), std::abs(d.perPascal) * 100 / r3 * L, 1e-15);
  EXPECT_NEAR(contributor(b, "u_λ,RH"), std::abs(d.perPercent) * 6 / r3 * L, 1e-15);
  EXPECT_NEAR(contributor(b, "u_DEADPATH"), 120 * std::hypot(d.perKelvin * 0.4, d.perPascal * 150) / r3, 1e-15);
  EXPECT_NEAR(contributor(b, "u_M,MACHINE"), 11.5e-6 * 0.2 / r3 * L, 1e-15);
  EXPECT_NEAR(contributor(b, "u_E,MACHINE"), 2e-6 * 1.4 / r3 * L, 1e-15);
  EXPECT_NEAR(contributor(b, "u_MISALIGNMENT"), 0.5 * 0.5 / (2 * L) / r3, 1e-15);  // L (1 - cos(d / L))
  EXPECT_NEAR(contributor(b, "u_EVE"), 1.2e-3 / r3, 1e-15);
  // Magnitudes a laser user would recognise: about 0.1 um per K of air sensor bound per 100 mm.
  EXPECT_NEAR(contributor(b, "u_λ,T") / kMicro, 0.95 * 0.2 / r3 * 0.8, 0.01);
}

TEST(PositioningUncertainty, EachValueCombinesItsContributorsAndItsCycles) {
  const auto test = eightHundredMillimetres();
  const auto result = evaluatePositioning(test);
  const auto b = positioningUncertainty(test, result, laserConditions());
  const double s = std::sqrt(2.5) * kMicro, n = 5;
  const auto sq = [&](const char* k) { return std::pow(contributor(b, k), 2); };
  const double lengthProportional = sq("u_DEVICE") + sq("u_λ,T") + sq("u_λ,p") + sq("u_λ,RH") + sq("u_M,MACHINE") + sq("u_E,MACHINE") +
                                    sq("u_MISALIGNMENT");
  const double everyValue = sq("u_DEADPATH") + sq("u_EVE");
  // A ranges over the targets: mean and 2 s at two of them, s known to 1 / sqrt(2 (n - 1)).
  const double statA = s * std::sqrt(2 / n + 4 / (n - 1));
  EXPECT_NEAR(b.at("A").statistical, statA, 1e-15);
  EXPECT_NEAR(b.at("A").combined, std::sqrt(statA * statA + lengthProportional + sq("u_DEVICE,0") + everyValue), 1e-15);
  EXPECT_DOUBLE_EQ(b.at("A").expanded, 2 * b.at("A").combined);
  EXPECT_NEAR(b.at("E").statistical, s * std::sqrt(2 / n), 1e-15);
  EXPECT_NEAR(b.at("M").statistical, s / std::sqrt(n), 1e-15);
  // B compares the directions at one target: the length-proportional contributors cancel.
  EXPECT_NEAR(b.at("B").combined, std::sqrt(2 * s * s / n + sq("u_DEVICE,0") + everyValue), 1e-15);
  // R is 4 s (or 2 s↑ + 2 s↓ + |B|): only its estimate's spread and what changes in time.
  EXPECT_NEAR(b.at("R").statistical, result.repeatability / std::sqrt(2 * (n - 1)), 1e-15);
  EXPECT_NEAR(b.at("R").combined, std::sqrt(std::pow(b.at("R").statistical, 2) + everyValue), 1e-15);
  EXPECT_EQ(b.quantities.size(), 11u);
}

TEST(PositioningUncertainty, DefaultsAreListedAndTheInstrumentMustSuitTheAxis) {
  const auto test = eightHundredMillimetres();
  const auto result = evaluatePositioning(test);
  const auto defaults = defaultMeasurementConditions(InstrumentType::Laser);
  EXPECT_EQ(defaults.defaulted.size(), 11u);
  const auto b = positioningUncertainty(test, result, defaults);
  for (const auto& k : b.contributors) EXPECT_TRUE(k.defaulted) << k.symbol;
  auto rotary = test;
  rotary.axis = PositioningAxis::Rotary;
  EXPECT_THROW(positioningUncertainty(rotary, result, defaults), InvalidInput);
  EXPECT_THROW(positioningUncertainty(test, result, defaultMeasurementConditions(InstrumentType::Angle)), InvalidInput);
  const auto angle = positioningUncertainty(rotary, result, defaultMeasurementConditions(InstrumentType::Angle));
  EXPECT_NEAR(contributor(angle, "u_DEVICE"), 0.5 * kArcsec, 1e-15);
  EXPECT_EQ(angle.contributors.size(), 2u);  // the device and the drift: no length contributors
}

TEST(Tolerance, EveryFormAtItsLengths) {
  const auto t = [](const char* text) { return parseTolerance(text, Dimension::Length, "t", true); };
  EXPECT_DOUBLE_EQ(t("8 um").at(5000), 0.008);
  EXPECT_DOUBLE_EQ(t("0.010 mm for 1000 mm").at(300), 0.003);  // ISO 230-1's proportionality
  EXPECT_DOUBLE_EQ(t("0.010 mm for 1000 mm, min 0.005 mm").at(300), 0.005);
  const auto increment = t("0.010 mm for 1000 mm, + 0.005 mm per additional 1000 mm, max 0.020 mm");
  EXPECT_DOUBLE_EQ(increment.at(600), 0.010);
  EXPECT_DOUBLE_EQ(increment.at(1500), 0.0125);
  EXPECT_DOUBLE_EQ(increment.at(5000), 0.020);
  const auto stepped = t("22 um up to 500 mm; 25 um up to 800 mm; 32 um up to 1250 mm");
  EXPECT_DOUBLE_EQ(stepped.at(500), 0.022);
  EXPECT_DOUBLE_EQ(stepped.at(501), 0.025);
  EXPECT_DOUBLE_EQ(stepped.at(1250), 0.032);
  EXPECT_THROW(stepped.at(1300), InvalidInput);
  for (const char* bad : {"", "-1 um", "8", "8 um, max 9 um", "1 um for 0 mm", "2 um for 100 mm, + 1 um", "2 um up to 500 mm; 3 um up to 400 mm",
                          "2 um for 100 mm, min 3 um, max 2.5 um", "2 um for 100 mm, bigger 3 um", "2 arcsec"})
    EXPECT_THROW(t(bad), InputError) << bad;
  EXPECT_THROW(parseTolerance("5 arcsec for 100 mm", Dimension::Angle, "t", false), InputError);
  EXPECT_DOUBLE_EQ(parseTolerance("5 arcsec", Dimension::Angle, "t", false).at(6.28), 5 * kArcsec);
}

TEST(Conformance, DecisionRules) {
  EXPECT_EQ(decide(10, 2, 12, DecisionRule::Iso14253_1), Verdict::Pass);  // 10 + 2 within 12
  EXPECT_EQ(decide(10.5, 2, 12, DecisionRule::Iso14253_1), Verdict::Undecided);
  EXPECT_EQ(decide(13.5, 2, 12, DecisionRule::Iso14253_1), Verdict::Undecided);
  EXPECT_EQ(decide(14.5, 2, 12, DecisionRule::Iso14253_1), Verdict::Fail);
  EXPECT_EQ(decide(11.9, 2, 12, DecisionRule::Simple), Verdict::Pass);
  EXPECT_EQ(decide(12.1, 2, 12, DecisionRule::Simple), Verdict::Fail);
}

const std::string kStage = bundledDataDir() + "/positioning/ecmc-motion-stage";

TEST(Conformance, RealMotionStageWithItsToleranceFile) {
  const auto e = evaluatePositioningFile({kStage + ".dat", kStage + "-conditions.yaml", kStage + "-tolerances.yaml"});
  ASSERT_TRUE(e.conformance);
  const auto& c = *e.conformance;
  EXPECT_EQ(c.rule, DecisionRule::Iso14253_1);
  ASSERT_EQ(c.verdicts.size(), 5u);
  std::map<std::string, Verdict> expected{{"A", Verdict::Pass}, {"B", Verdict::Undecided}, {"E", Verdict::Undecided},
                                          {"M", Verdict::Fail}, {"R", Verdict::Pass}};
  for (const auto& v : c.verdicts) {
    EXPECT_EQ(v.verdict, expected.at(v.quantity)) << v.quantity;
    // The rule itself: pass only with U inside, fail only with U outside.
    if (v.verdict == Verdict::Pass) {
      EXPECT_LE(v.value + v.expanded, v.tolerance) << v.quantity;
    } else if (v.verdict == Verdict::Fail) {
      EXPECT_GT(v.value - v.expanded, v.tolerance) << v.quantity;
    } else {
      EXPECT_LT(std::abs(v.value - v.tolerance), v.expanded) << v.quantity;
    }
    EXPECT_DOUBLE_EQ(v.expanded, e.uncertainty.at(v.quantity).expanded);
  }
  EXPECT_EQ(c.overall(), Verdict::Fail);
  // The tolerances at the stage's 40 mm: 32 um (the increment starts past 1000 mm), 4 um (0.010 mm
  // per 100 mm is 4 um, the minimum), 25 um (the first step).
  EXPECT_NEAR(c.verdicts[0].tolerance, 0.032, 1e-15);
  EXPECT_NEAR(c.verdicts[3].tolerance, 0.004, 1e-15);
  EXPECT_NEAR(c.verdicts[4].tolerance, 0.025, 1e-15);
}

TEST(Conformance, ResultWithinUOfItsToleranceIsUndecided) {
  const auto e = evaluatePositioningFile({kStage + ".dat", kStage + "-conditions.yaml", std::nullopt});
  const auto& E = e.uncertainty.at("E");
  ASSERT_GT(E.expanded, 0);
  for (const double f : {-0.99, -0.5, 0.0, 0.5, 0.99})
    EXPECT_EQ(decide(E.value, E.expanded, E.value + f * E.expanded, DecisionRule::Iso14253_1), Verdict::Undecided) << f;
  EXPECT_EQ(decide(E.value, E.expanded, E.value + 1.01 * E.expanded, DecisionRule::Iso14253_1), Verdict::Pass);
  EXPECT_EQ(decide(E.value, E.expanded, E.value - 1.01 * E.expanded, DecisionRule::Iso14253_1), Verdict::Fail);
  EXPECT_EQ(decide(E.value, E.expanded, E.value + 0.5 * E.expanded, DecisionRule::Simple), Verdict::Pass);
}

TEST(Conformance, ToleranceFileErrorsNameTheirLineAndKey) {
  const auto error = [](const std::string& yaml) {
    try {
      parseTolerances(yaml, "t.yaml");
    } catch (const InputError& e) {
      return e.where().key + "@" + std::to_string(e.where().line) + ": " + e.reason();
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("positioning:\n  A: 8 um\n  Q: 1 um\n").substr(0, 16), "positioning.Q@3:");
  EXPECT_EQ(error("decision_rule: lenient\n").substr(0, 16), "decision_rule@1:");
  EXPECT_EQ(error("positioning:\n  A: 8\n").substr(0, 16), "positioning.A@2:");
  EXPECT_EQ(error("ballbar:\n  A: 8 um\n").substr(0, 10), "ballbar@1:");
  // A tolerance file without the test's section is refused, not ignored.
  EXPECT_THROW(evaluatePositioningFile({kStage + ".dat", std::nullopt, bundledDataDir() + "/positioning/rotary-tolerances.yaml"}),
               InputError);
}

// The first ```yaml block after a heading of docs/file-formats.md.
std::string documentedExample(const std::string& heading) {
  std::ifstream in(test::testDataDir() + "/../../docs/file-formats.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const auto section = page.find("## " + heading);
  const auto start = page.find("```yaml\n", section);
  const auto end = page.find("```", start + 8);
  if (section == std::string::npos || start == std::string::npos || end == std::string::npos) return {};
  return page.substr(start + 8, end - start - 8);
}

TEST(Conformance, TheDocumentedExamplesRead) {
  const auto conditions = parseMeasurementConditions(documentedExample("Measurement conditions (YAML)"), "file-formats.md");
  EXPECT_EQ(conditions.instrument, "laser interferometer XL-80");
  EXPECT_DOUBLE_EQ(conditions.airPressure.value, 100100);
  EXPECT_EQ(conditions.defaulted.size(), 0u);
  const auto tolerances = parseTolerances(documentedExample("Tolerances (YAML)"), "file-formats.md");
  EXPECT_EQ(tolerances.entries.size(), 6u);
  const auto acceptance = parseAcceptancePlan(documentedExample("Acceptance tests (YAML)"), "file-formats.md");
  EXPECT_EQ(acceptance.tests.size(), 5u);
}

}  // namespace
}  // namespace mtacc
