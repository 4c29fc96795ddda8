// Seed 002 (Applied Sciences 10, 1811): ballbar tests on the multi-tasking machine
// w-C'bZYXB(C1)-t. The exact simulation on the generic model, through the seed-002 aliases
// (docs/conventions.md), must reproduce the first-order relations of Table 5 (L1587-1634,
// verified in reference seed002_ballbar_multitasking.md §9), and the generic least squares
// must recover the twelve deviations of Table 7 from the six simulated runs of §5.3.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include <fmt/format.h>

#include "mtacc/errors/aliases.hpp"
#include "mtacc/measurement/circular_evaluation.hpp"
#include "mtacc/identification/identification.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/procedures/ballbar_seed002.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

using Deviations = std::map<std::string, double>;


// Seed 002's deviations (Table 1 names) as an ISO error state of the bundled machine.
ErrorModel seed002Errors(const Machine& m, const Deviations& d) {
  ErrorModel e = ErrorModel::zero(m);
  for (const auto& [name, value] : d) {
    const auto alias = findAlias(name);
    for (const auto& part : alias->terms) {
      const auto p = findParameter(m, e, part.isoName);
      setParameterValue(e, p, parameterValue(e, p) + part.sign * value);
    }
  }
  return e;
}

struct Geometry {
  double lB, zC, rB, rC;
};

// One of the seed's tests (Table 2), simulated exactly over a full turn of 360 points.
MeasurementRun simulatedTest(const KinematicModel& model, const KinematicModel& nominal, const std::string& axis,
                  RotaryTestMode mode, const Geometry& g) {
  BallbarRotarySpec spec;
  spec.axis = axis;
  spec.mode = mode;
  spec.length = g.lB;
  spec.toolBall = Vec3(0, 0, -(g.rB - 150.0));  // the bundled machine's TCP is 150 mm from the B centre
  spec.workBall = axis == "B" ? Vec3(0, 0, g.zC) : Vec3(g.rC, 0, g.zC);
  spec.points = 360;
  auto run = ballbarRotaryTest(nominal, spec);
  simulateRun(model, nominal, run);
  return run;
}

// Its eccentricity: first and second harmonics fitted (reference §8).
Vec3 eccentricity(const KinematicModel& model, const KinematicModel& nominal, const std::string& axis,
                  RotaryTestMode mode, const Geometry& g) {
  return fitEccentricity(simulatedTest(model, nominal, axis, mode, g)).eccentricity;
}

// Table 5 (plus the reference's CX/CY/BR/BT rows are not used here): ex, ey, ez of each test.
struct Expected {
  Vec3 bx, by, bz, cr, ct, ca;
};
Expected table5(const Deviations& d, const Geometry& g) {
  auto v = [&](const char* n) { return d.count(n) ? d.at(n) : 0.0; };
  const double dxBT = v("dxBT"), dzBT = v("dzBT"), aBT = v("alphaBT"), aXB = v("alphaXB"), bXB = v("betaXB"),
               cXB = v("gammaXB"), aYZ = v("alphaYZ"), bYZ = v("betaYZ"), dxCZ = v("dxCZ"), dyCZ = v("dyCZ"),
               aCZ = v("alphaCZ"), bCZ = v("betaCZ");
  Expected e;
  e.bx = Vec3(dzBT, 0, dxBT - g.rB * bXB - g.rB * bYZ);
  e.by = Vec3(-g.rB * cXB, 0, g.rB * aXB + g.rB * aYZ);
  e.bz = Vec3(g.rB * bXB - dxBT, 0, dzBT);
  e.cr = Vec3(-dxBT + g.rB * bXB + dxCZ + g.zC * bCZ + g.rB * bYZ,
              -g.rB * aXB - g.rB * aBT + dyCZ - g.zC * aCZ - g.rB * aYZ, 0);
  e.ct = Vec3(-e.cr.y(), e.cr.x(), 0);
  e.ca = Vec3(g.rC * bCZ - g.rC * bYZ, g.rC * aYZ - g.rC * aCZ, 0);
  return e;
}

const char* kNames[] = {"dxBT", "dzBT", "alphaBT", "alphaXB", "betaXB", "gammaXB", "gammaXY",
                        "alphaYZ", "betaYZ", "dxCZ", "dyCZ", "alphaCZ", "betaCZ"};

// §4 (L303): L_B = 100, Z_C = 100, R_B = 200, R_C = 50 mm; each deviation alone at +20 um
// or +0.005 deg. Table 5 is first order; the exact model differs by second-order terms of
// about e^2 / L_B = 4e-6 mm, so the tolerance is 0.01 um.
TEST(Seed002Ballbar, Table5FirstOrderRelationsFromTheExactSimulation) {
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  const Geometry g{100, 100, 200, 50};
  for (const char* name : kNames) {
    const bool angle = name[0] == 'a' || name[0] == 'b' || name[0] == 'g';
    const Deviations d{{name, angle ? 0.005 * kDeg : 20e-3}};
    const auto model = compile(machine, seed002Errors(*machine, d));
    const auto e = table5(d, g);
    const double tol = 1e-5;
    SCOPED_TRACE(name);
    EXPECT_LT((eccentricity(model, nominal, "B", RotaryTestMode::X, g) - e.bx).norm(), tol) << "B X-direction";
    EXPECT_LT((eccentricity(model, nominal, "B", RotaryTestMode::Y, g) - e.by).norm(), tol) << "B Y-direction";
    EXPECT_LT((eccentricity(model, nominal, "B", RotaryTestMode::Z, g) - e.bz).norm(), tol) << "B Z-direction";
    EXPECT_LT((eccentricity(model, nominal, "C", RotaryTestMode::Radial, g) - e.cr).norm(), tol) << "C radial";
    EXPECT_LT((eccentricity(model, nominal, "C", RotaryTestMode::Tangential, g) - e.ct).norm(), tol) << "C tangential";
    EXPECT_LT((eccentricity(model, nominal, "C", RotaryTestMode::Axial, g) - e.ca).norm(), tol) << "C axial";
  }
}

// Table 2's twelve tests, in Table 3's row order, with the seed's line of each row.
struct TestRow {
  const char* name;
  const char* axis;
  RotaryTestMode mode;
  int line;
};
const TestRow kTwelveTests[] = {{"B radial", "B", RotaryTestMode::Radial, 1294},     {"B tangential", "B", RotaryTestMode::Tangential, 1311},
                                {"B axial", "B", RotaryTestMode::Axial, 1328},       {"B X", "B", RotaryTestMode::X, 1345},
                                {"B Y", "B", RotaryTestMode::Y, 1364},               {"B Z", "B", RotaryTestMode::Z, 1383},
                                {"C radial", "C", RotaryTestMode::Radial, 1402},     {"C tangential", "C", RotaryTestMode::Tangential, 1419},
                                {"C axial", "C", RotaryTestMode::Axial, 1436},       {"C X", "C", RotaryTestMode::X, 1453},
                                {"C Y", "C", RotaryTestMode::Y, 1467},               {"C Z", "C", RotaryTestMode::Z, 1482}};

// A deviation or mounting error "affects" a test when its dL trace moves by more than 0.05 um:
// the first-order effects of §4's sizes are 2.18 um and more (reference §12.1), the second-order
// ones about e^2 / L_B = 0.004 um.
constexpr double kAffects = 0.05e-3;
double largestChange(const MeasurementRun& run) { return run.readings.cwiseAbs().maxCoeff(); }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// Table 3 (L1275-1502): the polar plots of dL in each of the twelve tests with each deviation
// alone at +20 um or +0.005 deg (§4, L303); the printed result is which deviations change which
// test (a plot drawn, or blank), transcribed in reference §12.1 (two cells of rows C X and C Y
// survive only through the image numbering, i057 and i068). L_B 100, Z_C 100, R_B 200, R_C 50 mm.
TEST(Seed002Ballbar, Table3WhichDeviationsChangeWhichOfTheTwelveTests) {
  const std::map<std::string, std::vector<std::string>> printed{
      {"B radial", {"dxBT", "dzBT", "betaXB", "betaYZ"}},
      {"B tangential", {"dxBT", "dzBT", "betaXB", "betaYZ"}},
      {"B axial", {"alphaXB", "gammaXB", "alphaYZ"}},
      {"B X", {"dxBT", "dzBT", "betaXB", "betaYZ"}},
      {"B Y", {"alphaXB", "gammaXB", "alphaYZ"}},
      {"B Z", {"dxBT", "dzBT", "betaXB"}},
      {"C radial", {"dxBT", "alphaBT", "alphaXB", "betaXB", "gammaXY", "alphaYZ", "betaYZ", "dxCZ", "dyCZ", "alphaCZ", "betaCZ"}},
      {"C tangential", {"dxBT", "alphaBT", "alphaXB", "betaXB", "gammaXY", "alphaYZ", "betaYZ", "dxCZ", "dyCZ", "alphaCZ", "betaCZ"}},
      {"C axial", {"alphaYZ", "betaYZ", "alphaCZ", "betaCZ"}},
      {"C X", {"dxBT", "alphaBT", "alphaXB", "betaXB", "alphaYZ", "betaYZ", "dxCZ", "dyCZ", "alphaCZ", "betaCZ"}},
      {"C Y", {"dxBT", "alphaBT", "alphaXB", "betaXB", "gammaXY", "alphaYZ", "betaYZ", "dxCZ", "dyCZ", "alphaCZ", "betaCZ"}},
      {"C Z", {"alphaYZ", "betaYZ", "alphaCZ", "betaCZ"}}};
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  const Geometry g{100, 100, 200, 50};
  std::map<std::string, KinematicModel> models;
  for (const char* name : kNames) {
    const bool angle = name[0] == 'a' || name[0] == 'b' || name[0] == 'g';
    models.emplace(name, compile(machine, seed002Errors(*machine, {{name, angle ? 0.005 * kDeg : 20e-3}})));
  }
  for (const auto& t : kTwelveTests) {
    std::vector<std::string> affecting;
    for (const char* name : kNames)
      if (largestChange(simulatedTest(models.at(name), nominal, t.axis, t.mode, g)) > kAffects) affecting.push_back(name);
    const auto& paper = printed.at(t.name);
    const auto sorted = [&](std::vector<std::string> v) { return std::set<std::string>(v.begin(), v.end()); };
    const bool same = sorted(affecting) == sorted(paper);
    const test::Statement statement{"002", fmt::format("Table 3, L{}", t.line), fmt::format("deviations that change {}", t.name), joined(paper)};
    if (std::string(t.name) == "C X" || std::string(t.name) == "C Y")
      test::expectStatementFails(statement, same, joined(affecting),
                                 "gammaXY: with the W ball set at the actual T ball (Eqs 11-12, L225) the C axis' X test sees "
                                 "R_C gammaXY and its Y test nothing; the paper's pattern needs that set-up error left out "
                                 "(reference §7); the 12-parameter identification is not affected");
    else
      test::expectStatementHolds(statement, same, joined(affecting), "the exact simulation, 0.05 um threshold");
  }
}

// Table 4 (L1506-1586) and §4.1 (L329-360): each mounting error alone at 20 um (L332); xT yT zT
// offset the T ball in the tool frame (Eq 15), xW yW zW the W ball from the actual T ball in the
// C frame (Eq 16). Of the table only the B radial row survives (L1530-1549: plots for xW, zW, xT,
// zT); the text states which tests the W ball leaves alone (L358) and that the C Y test is
// disturbed by both balls (L368).
TEST(Seed002Ballbar, Table4MountingErrorsAndTheChoiceOfTests) {
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  const Geometry g{100, 100, 200, 50};
  const std::pair<const char*, SetupParameter> mounting[] = {{"xW", SetupParameter::TargetX},   {"yW", SetupParameter::TargetY},
                                                             {"zW", SetupParameter::TargetZ},   {"xT", SetupParameter::ToolBallX},
                                                             {"yT", SetupParameter::ToolBallY}, {"zT", SetupParameter::ToolBallZ}};
  // dL and eccentricity of each test with each mounting error alone.
  auto withMounting = [&](const TestRow& t, SetupParameter p) {
    BallbarRotarySpec spec;
    spec.axis = t.axis;
    spec.mode = t.mode;
    spec.length = g.lB;
    spec.toolBall = Vec3(0, 0, -(g.rB - 150.0));
    spec.workBall = std::string(t.axis) == "B" ? Vec3(0, 0, g.zC) : Vec3(g.rC, 0, g.zC);
    auto run = ballbarRotaryTest(nominal, spec);
    run.setup.errors[static_cast<size_t>(p)] = 20e-3;
    simulateRun(nominal, nominal, run);
    return std::pair{largestChange(run), fitEccentricity(run).eccentricity.norm()};
  };
  std::vector<std::string> changesBRadial;
  for (const auto& [name, p] : mounting)
    if (withMounting(kTwelveTests[0], p).first > kAffects) changesBRadial.push_back(name);
  test::expectStatementHolds({"002", "Table 4, L1530-1549", "mounting errors that change B radial", "xW, zW, xT, zT"},
                             changesBRadial == std::vector<std::string>{"xW", "zW", "xT", "zT"}, joined(changesBRadial),
                             "the W ball set at the actual T ball, its offset included (reference §6)");
  // L358: the W ball's errors leave the eccentricity of the B X, B Y, B Z, C radial, C tangential
  // and C axial tests (the chosen ones) alone; the T ball's move both kinds of test.
  double wChosen = 0, tCartesian = 0, tCylindrical = 0;
  for (const auto& t : kTwelveTests) {
    const std::string n = t.name;
    const bool chosen = n == "B X" || n == "B Y" || n == "B Z" || n == "C radial" || n == "C tangential" || n == "C axial";
    const bool cartesian = t.mode == RotaryTestMode::X || t.mode == RotaryTestMode::Y || t.mode == RotaryTestMode::Z;
    for (const auto& [name, p] : mounting) {
      const double e = withMounting(t, p).second;
      if (name[1] == 'W' && chosen) wChosen = std::max(wChosen, e);
      if (name[1] == 'T') (cartesian ? tCartesian : tCylindrical) = std::max(cartesian ? tCartesian : tCylindrical, e);
    }
  }
  test::expectStatementHolds({"002", "Section 4.1, L358", "W-ball mounting errors do not move the eccentricity of the six chosen tests",
                              "0 in B X, B Y, B Z, C radial, C tangential, C axial"},
                             wChosen < kAffects, fmt::format("largest {:.4f} um of 20 um", wChosen * 1e3), "the exact simulation, 0.05 um threshold");
  test::expectStatementHolds({"002", "Section 4.1, L358", "T-ball mounting errors strongly affect the eccentricity in both coordinate systems",
                              "strongly, Cartesian and cylindrical tests"},
                             tCartesian > 10e-3 && tCylindrical > 10e-3,
                             fmt::format("largest {:.1f} um (Cartesian), {:.1f} um (cylindrical) of 20 um", tCartesian * 1e3, tCylindrical * 1e3),
                             "more than half the 20 um offset in both");
  double wY = 0, tY = 0;
  for (const auto& [name, p] : mounting) (name[1] == 'W' ? wY : tY) = std::max(name[1] == 'W' ? wY : tY, withMounting(kTwelveTests[10], p).second);
  test::expectStatementHolds({"002", "Section 4.2, L368", "C Y test strongly affected by W- and T-ball mounting errors", "strongly, both balls"},
                             wY > 10e-3 && tY > 10e-3, fmt::format("eccentricity {:.1f} um (W), {:.1f} um (T) of 20 um", wY * 1e3, tY * 1e3),
                             "more than half the 20 um offset for each ball");
}

// §5.4 (L567-575): Table 7's initial deviations (L1758-1835); gammaXY is not given (0).
const double um = 1e-3, as = kArcsec;
const Deviations kTable7Initial{{"dxBT", 11.00 * um},   {"dzBT", 17.00 * um},   {"alphaBT", 7.63 * as},
                                {"alphaXB", 3.51 * as}, {"betaXB", 3.92 * as},  {"gammaXB", 6.39 * as},
                                {"alphaYZ", 2.27 * as}, {"betaYZ", 4.74 * as},  {"dxCZ", 13.00 * um},
                                {"dyCZ", 7.00 * um},    {"alphaCZ", 2.06 * as}, {"betaCZ", 5.98 * as}};
const Deviations kTable7Identified{{"dxBT", 10.96 * um},  {"dzBT", 16.63 * um},   {"alphaBT", 7.69 * as},
                                   {"alphaXB", 3.44 * as}, {"betaXB", 3.80 * as},  {"gammaXB", 6.44 * as},
                                   {"alphaYZ", 2.32 * as}, {"betaYZ", 4.79 * as},  {"dxCZ", 13.01 * um},
                                   {"dyCZ", 6.96 * um},    {"alphaCZ", 2.11 * as}, {"betaCZ", 5.98 * as}};
// The seed's line of each deviation in Table 7.
const std::map<std::string, int> kTable7Lines{{"dxBT", 1758},    {"dzBT", 1765},    {"alphaBT", 1772}, {"alphaXB", 1779},
                                              {"betaXB", 1786},  {"gammaXB", 1793}, {"alphaYZ", 1800}, {"betaYZ", 1807},
                                              {"dxCZ", 1814},    {"dyCZ", 1821},    {"alphaCZ", 1828}, {"betaCZ", 1835}};
// L570 and the footnotes of Table 6: R_C 50, R_B 360, R_B'' 410, Z_C 300, Z_C' 340 mm;
// L_B is not stated, 100 mm as in §4.
const Geometry kStep1{100, 300, 360, 50}, kStep2{100, 340, 360, 50}, kStep3{100, 340, 410, 50};

// The six runs of §5.3: B X, B Y, C axial and C radial at step 1, C radial at steps 2 and 3.
std::vector<MeasurementRun> sixRuns(const KinematicModel& model, const KinematicModel& nominal) {
  std::vector<MeasurementRun> runs = {simulatedTest(model, nominal, "B", RotaryTestMode::X, kStep1),
                           simulatedTest(model, nominal, "B", RotaryTestMode::Y, kStep1),
                           simulatedTest(model, nominal, "C", RotaryTestMode::Axial, kStep1),
                           simulatedTest(model, nominal, "C", RotaryTestMode::Radial, kStep1),
                           simulatedTest(model, nominal, "C", RotaryTestMode::Radial, kStep2),
                           simulatedTest(model, nominal, "C", RotaryTestMode::Radial, kStep3)};
  const char* names[] = {"BX", "BY", "CA", "CR", "CR1", "CR2"};
  for (size_t i = 0; i < runs.size(); ++i) runs[i].name = names[i];
  return runs;
}

// Seed values from the identified ISO ones (inverse of the alias terms).
Deviations seed002FromIso(const Machine& m, const ErrorModel& e) {
  auto v = [&](const char* iso) { return parameterValue(e, findParameter(m, e, iso)); };
  return {{"dxBT", v("X0C1")}, {"dzBT", v("Z0C1")}, {"alphaBT", v("A0C1")}, {"alphaXB", v("A0B") - v("A0Y")},
          {"betaXB", v("B0B") - v("B0X")}, {"gammaXB", v("C0B") - v("C0X")}, {"alphaYZ", v("A0Y")},
          {"betaYZ", v("B0X")}, {"dxCZ", v("X0C")}, {"dyCZ", v("Y0C")}, {"alphaCZ", v("A0C")}, {"betaCZ", v("B0C")}};
}

const std::vector<std::string> kIsoTwelve = {"X0C1", "Z0C1", "A0C1", "A0B", "B0B", "C0B",
                                             "A0Y",  "B0X",  "X0C",  "Y0C", "A0C", "B0C"};

// Reference section 12.2: the closed forms applied to an exact simulation of the initial values
// return them within 0.052 arcsec and 0.013 um (second-order terms, e^2 / L_B). The simulated
// eccentricities themselves are compared with Table 6 (L1635-1748), printed to 0.01 um.
TEST(Seed002Ballbar, Eqs17To28RecoverTable7InitialFromTheExactSimulation) {
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  const auto model = compile(machine, seed002Errors(*machine, kTable7Initial));
  const auto runs = sixRuns(model, nominal);
  std::vector<Vec3> e;
  for (const auto& r : runs) e.push_back(fitEccentricity(r).eccentricity);
  Seed002Eccentricities ecc{e[0].x(), e[0].z(), e[1].x(), e[1].z(), e[2].x(), e[2].y(),
                            e[3].x(), e[3].y(), e[4].x(), e[4].y(), e[5].x(), e[5].y()};
  const auto d = identifySeed002(ecc, Seed002Setup{360, 410, 50, 300, 340});
  const Deviations got{{"dxBT", d.dxBT},       {"dzBT", d.dzBT},       {"alphaBT", d.alphaBT}, {"alphaXB", d.alphaXB},
                       {"betaXB", d.betaXB},   {"gammaXB", d.gammaXB}, {"alphaYZ", d.alphaYZ}, {"betaYZ", d.betaYZ},
                       {"dxCZ", d.dxCZ},       {"dyCZ", d.dyCZ},       {"alphaCZ", d.alphaCZ}, {"betaCZ", d.betaCZ}};
  for (const auto& [name, truth] : kTable7Initial) {
    const bool angle = name[0] != 'd';
    EXPECT_NEAR(got.at(name), truth, angle ? 0.06 * as : 0.015 * um) << name;
  }
  // Table 6 against the exact simulation of Table 7's initial values. The paper's Table 6 is
  // not the first-order prediction of those values either: it differs from it by up to 0.37
  // um (e_x of B X), which the paper does not explain; a T-ball offset of about (0.09, 0.19,
  // -0.37) um reproduces 10 of the 12 (reference section 12.2). Those of C axial agree.
  struct Entry {
    const char* run;
    const char* component;
    double printed;
    bool reproduced;
    double today;
  };
  const Entry entries[] = {{"B X", "ex", 16.63, false, 17.002},         {"B X", "ez", -4.02, false, -4.118},
                           {"B Y", "ex", -11.24, false, -11.151},       {"B Y", "ez", 10.05, false, 10.085},
                           {"C axial", "ex", 0.29, true, 0.289},        {"C axial", "ey", 0.05, true, 0.051},
                           {"C radial (a)", "ex", 25.73, false, 25.809}, {"C radial (a)", "ey", -19.59, false, -19.406},
                           {"C radial (b)", "ex", 26.89, false, 26.968}, {"C radial (b)", "ey", -20.00, false, -19.806},
                           {"C radial (c)", "ex", 28.97, false, 29.066}, {"C radial (c)", "ey", -23.26, false, -23.058}};
  const double simulated[] = {ecc.bxEx, ecc.bxEz, ecc.byEx, ecc.byEz, ecc.caEx, ecc.caEy,
                              ecc.crEx, ecc.crEy, ecc.cr1Ex, ecc.cr1Ey, ecc.cr2Ex, ecc.cr2Ey};
  for (size_t i = 0; i < std::size(entries); ++i) {
    const auto& en = entries[i];
    const test::Printed p{"002", "Table 6, L1635-1748", fmt::format("{} {}", en.run, en.component), en.printed, 2, "um"};
    if (en.reproduced)
      test::expectReproduced(p, simulated[i] / um, 0.005, "half the printed digit");
    else
      test::expectKnownDifference(p, simulated[i] / um, en.today, 0.001,
                                  "Table 6 differs from the first-order prediction of Table 7's initial values by up to 0.37 um, "
                                  "unexplained in the paper (reference section 12.2)");
  }
}

// The generic least squares on the full dL traces of the same six runs: the twelve ISO
// parameters (A0Y, B0X for the seed's squareness) are observable and come back as Table
// 7's initial values (noise-free data: to 1e-6 um / 1e-6 arcsec), hence within the paper's
// own identified values' stated differences (L574: 0.37 um, 0.12 arcsec, met with equality
// by betaXB, plus half the printed digit).
TEST(Seed002Ballbar, Table7FromGenericLeastSquaresOnTheSixRuns) {
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  const auto truth = seed002Errors(*machine, kTable7Initial);
  IdentificationProblem problem;
  problem.machine = machine;
  problem.start = ErrorModel::zero(*machine);
  for (const auto& n : kIsoTwelve) problem.parameters.push_back(findParameter(*machine, problem.start, n));
  problem.runs = sixRuns(compile(machine, truth), nominal);
  const auto result = identify(problem);
  EXPECT_TRUE(result.observability.identifiable());
  EXPECT_TRUE(result.converged) << result.solverReport;
  const auto got = seed002FromIso(*machine, result.errors);
  for (const auto& [name, value] : kTable7Initial) {
    const bool angle = name[0] != 'd';
    const double unit = angle ? as : um;
    test::expectSelfConsistent({"002", "Table 7, L" + std::to_string(kTable7Lines.at(name)),
                                name + " recovered by least squares from the six runs simulated with its initial value", value / unit, 2,
                                angle ? "arcsec" : "um"},
                               got.at(name) / unit, 1e-6, "noise-free data");
    EXPECT_NEAR(got.at(name), kTable7Identified.at(name), angle ? 0.125 * as : 0.375 * um) << name;
  }
}

TEST(Seed002Ballbar, SixRunsDetermineTheTwelveDeviations) {
  const auto machine = test::bundled("multitasking-b-c");
  const auto nominal = compileNominal(machine);
  IdentificationProblem problem;
  problem.machine = machine;
  problem.start = ErrorModel::zero(*machine);
  for (const auto& n : kIsoTwelve) problem.parameters.push_back(findParameter(*machine, problem.start, n));
  problem.runs = sixRuns(nominal, nominal);
  const auto report = planObservability(problem);
  EXPECT_EQ(report.rank, 12);
  EXPECT_TRUE(report.identifiable());
  // gammaXY (C0X + C0B; C0X is the new column) moves no eccentricity of these runs
  // (L366-368), but the full traces carry it in C radial's second harmonic,
  // (L_B - R_C) gammaXY / 2 (reference §9): the generic fit can determine all 13.
  problem.parameters.push_back(findParameter(*machine, problem.start, "C0X"));
  EXPECT_EQ(planObservability(problem).rank, 13);
}

}  // namespace
}  // namespace mtacc
