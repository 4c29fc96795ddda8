// Seed 003 (TU Eindhoven BCR report), Appendix D: the Maho machine's individual model, thirteen
// piecewise-quadratic tables in the absolute axis position, bundled in data/machines/maho.yaml
// with the four OCR repairs of the reference extraction §8.4. Checked here: the extraction's
// check values (§8.3, computed from the tables and printed to five or six digits), C1
// continuity at every break (§8.1), and the derived error grid of §13 item 12 (Fig. 5.2's set-up:
// XZ plane at Y = 250, tool length L = 150, relative to (X, Z) = (0, 0)), which is a
// regression check of the extraction's reading of the model (conventions in
// docs/conventions.md, "Seed 003 individual model").
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <fmt/format.h>
#include <initializer_list>

#include "mtacc/kinematics/forward.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct AppendixD {
  std::shared_ptr<const Machine> machine = test::bundled("maho");
  ErrorModel errors = loadMachineErrors(*machine);

  // The error function of a seed 003 component name (xrx, ztz, ...).
  const ErrorFunction& component(const std::string& seedName) const { return test::seed003Component(*machine, errors, seedName); }
  double arcsec(const std::string& name, double x) const { return component(name).value(x, 0) / kArcsec; }
};

// The seed's lines of each App. D table.
std::string tableLines(const std::string& name) {
  static const std::map<std::string, std::string> lines{
      {"xrx", "L5139-5149"}, {"xry", "L5159-5175"}, {"xrz", "L5185-5194"}, {"yrx", "L5205-5212"},
      {"yry", "L5222-5236"}, {"yrz", "L5249-5261"}, {"zrx", "L5274-5279"}, {"zry", "L5288-5302"},
      {"zrz", "L5313-5321"}, {"xtx", "L5333-5364"}, {"yty", "L5370-5377"}, {"ztz", "L5383-5388"}};
  return lines.at(name);
}

// A check value of the extraction §8.3, computed there from the printed table (the seed prints
// only the coefficients, L5139): evaluating the transcribed table checks the data entry, so it
// is input echoed, to half a unit in its last printed digit.
void expectCheckValue(const std::string& name, const std::string& what, double computed, double printed, int decimals,
                      const std::string& unit) {
  test::expectInputEchoed({"003", "App. D tables (check values of extraction §8.3), " + tableLines(name), what, printed, decimals, unit},
                         computed, 0.5 * std::pow(10.0, -decimals), "half the printed digit");
}

TEST(Seed003AppendixD, CheckValuesOfSection8_3) {
  // Extraction §8.3 (from the App. D tables, seed L5139-5388), rotations in arcsec. Each check
  // value lies at a break or inside an interval; at a break both sides agree to 1e-6 (C1 test).
  const AppendixD d;
  struct Check {
    const char* name;
    double x, value;
    int decimals;
  };
  const Check rotations[] = {
      {"xrx", 50, -0.28234, 5},  {"xrx", 100, -0.24955, 5}, {"xrx", 200, -0.73849, 5}, {"xrx", 300, -1.79335, 5},
      {"xrx", 400, -2.03613, 5}, {"xrx", 500, -1.13342, 5}, {"xrx", 600, -0.24365, 5}, {"xrx", 700, 0.90113, 5},
      {"xry", 100, 0.98170, 5},  {"xry", 350, 1.91181, 5},  {"xry", 500, 1.18058, 5},  {"xry", 700, 1.9070, 4},
      {"xrz", 100, -0.52871, 5}, {"xrz", 300, 2.05135, 5},  {"xrz", 500, 3.67913, 5},  {"xrz", 700, 6.4475, 4},
      {"yrx", 500, 2.5253, 4},   {"yry", 0, 0.35634, 5},    {"yry", 200, -0.63545, 5}, {"yry", 500, -3.1915, 4},
      {"yrz", 250, 1.12109, 5},  {"yrz", 450, 2.50943, 5},  {"yrz", 500, 2.8776, 4},   {"zrx", 200, -4.48336, 5},
      {"zrx", 400, -8.01014, 5}, {"zrx", 600, -12.187, 3},  {"zry", 300, -1.32399, 5}, {"zry", 600, -1.5845, 4},
      {"zrz", 400, 0.45650, 5},  {"zrz", 600, 1.4622, 4}};
  for (const auto& c : rotations)
    expectCheckValue(c.name, fmt::format("{}({:g})", c.name, c.x), d.arcsec(c.name, c.x), c.value, c.decimals, "arcsec");

  // Scale errors in mm; xtx's check value is the trend alone (its first term), L5333-5364.
  expectCheckValue("xtx", "xtx trend(700)", std::get<PiecewiseTerm>(d.component("xtx").terms()[0]).value(700), 0.013487, 6, "mm");
  expectCheckValue("yty", "yty(500)", d.component("yty").value(500, 0), 0.023927, 6, "mm");
  expectCheckValue("ztz", "ztz(200)", d.component("ztz").value(200, 0), 0.0074683, 7, "mm");
  expectCheckValue("ztz", "ztz(400)", d.component("ztz").value(400, 0), 0.0180414, 7, "mm");
  expectCheckValue("ztz", "ztz(600)", d.component("ztz").value(600, 0), 0.030679, 6, "mm");

  // xrx's minimum, -2.134" near x = 365, and the periodic term's extremes, -1.82 um near
  // u = 13.7 and +0.84 um near u = 27.6 (lambda = 39.6 mm): sought on a 0.01 mm grid.
  auto extreme = [](auto f, double from, double to, bool lowest) {
    std::pair<double, double> best{from, f(from)};
    for (double x = from; x <= to; x += 0.01)
      if (lowest ? f(x) < best.second : f(x) > best.second) best = {x, f(x)};
    return best;
  };
  const auto& xrx = d.component("xrx");
  const auto xrxMin = extreme([&](double x) { return xrx.value(x, 0) / kArcsec; }, 0, 700, true);
  expectCheckValue("xrx", "xrx minimum", xrxMin.second, -2.134, 3, "arcsec");
  EXPECT_NEAR(xrxMin.first, 365, 1.0);  // "x ≈ 365": to the mm
  const auto& periodic = std::get<PiecewiseTerm>(d.component("xtx").terms()[1]);
  EXPECT_DOUBLE_EQ(periodic.period, 39.6);
  const auto low = extreme([&](double u) { return periodic.value(u) / kMicro; }, 0, 39.6, true);
  const auto high = extreme([&](double u) { return periodic.value(u) / kMicro; }, 0, 39.6, false);
  expectCheckValue("xtx", "xtx periodic term, minimum", low.second, -1.82, 2, "um");
  expectCheckValue("xtx", "xtx periodic term, maximum", high.second, 0.84, 2, "um");
  // The extremes are the vertices of two quadratic pieces, u = 13.69 and 27.54; the printed
  // "u ≈ 13.7" and "u ≈ 27.6" are read off a coarser sampling, so they hold to 0.1 mm.
  EXPECT_NEAR(low.first, 13.7, 0.1);
  EXPECT_NEAR(high.first, 27.6, 0.1);
}

// Half a unit in the eighth significant digit of each printed term: how far two sides of a break
// can differ when the coefficients are printed to eight digits.
double printedRounding(std::initializer_list<double> terms) {
  double sum = 0.0;
  for (const double t : terms) sum += 5e-8 * std::abs(t);
  return sum;
}

TEST(Seed003AppendixD, EveryTableIsC1AtEveryBreak) {
  // §8.1: the tables are C1 in the absolute position: at every break both sides agree in value
  // and slope to the rounding of their printed terms (c0, c1 t, c2 t^2 and c1, 2 c2 t).
  const AppendixD d;
  int breaksChecked = 0;
  for (const char* name : {"xrx", "xry", "xrz", "yrx", "yry", "yrz", "zrx", "zry", "zrz", "xtx", "yty", "ztz"}) {
    for (const auto& term : d.component(name).terms()) {
      const auto& p = std::get<PiecewiseTerm>(term);
      if (p.period > 0.0) continue;  // xtx's periodic term: the next test
      const auto pieces = p.intervals();
      for (size_t i = 1; i < pieces.size(); ++i) {
        const double t = p.breaks[i];
        const auto& l = pieces[i - 1];
        const auto& r = pieces[i];
        EXPECT_NEAR(l[0] + l[1] * t + l[2] * t * t, r[0] + r[1] * t + r[2] * t * t,
                    printedRounding({l[0], l[1] * t, l[2] * t * t, r[0], r[1] * t, r[2] * t * t}))
            << name << " value at " << t;
        EXPECT_NEAR(l[1] + 2 * l[2] * t, r[1] + 2 * r[2] * t, printedRounding({l[1], 2 * l[2] * t, r[1], 2 * r[2] * t}))
            << name << " slope at " << t;
        ++breaksChecked;
      }
    }
  }
  EXPECT_EQ(breaksChecked, 7 + 13 + 6 + 4 + 3 + 9 + 2 + 11 + 5 + 9 + 4 + 2);
}

TEST(Seed003AppendixD, PeriodicTermIsC1AtQuartersOfItsFittedWavelength) {
  // xtx's periodic term (L5333-5364) has its breaks at quarters of lambda, printed as 39.6 mm
  // (L5343). At exactly 39.6 its slopes differ by up to 1.8e-9 mm/mm, 60 times the printed
  // rounding: the fit used a lambda given to more digits. Each break's slope condition
  // l1 + 2 l2 t = r1 + 2 r2 t gives that lambda independently; all three agree (39.59997 mm),
  // it rounds to the printed 39.6, and there the values agree to their rounding too.
  const AppendixD d;
  const auto& p = std::get<PiecewiseTerm>(d.component("xtx").terms()[1]);
  const auto pieces = p.intervals();
  ASSERT_EQ(pieces.size(), 4u);
  std::vector<double> lambdas;
  for (size_t i = 1; i < 4; ++i) {
    const auto& l = pieces[i - 1];
    const auto& r = pieces[i];
    const double t = (r[1] - l[1]) / (2 * (l[2] - r[2]));
    lambdas.push_back(4.0 * t / static_cast<double>(i));
    EXPECT_NEAR(l[0] + l[1] * t + l[2] * t * t, r[0] + r[1] * t + r[2] * t * t,
                printedRounding({l[0], l[1] * t, l[2] * t * t, r[0], r[1] * t, r[2] * t * t}))
        << "value at break " << i;
  }
  for (const double lambda : lambdas) {
    EXPECT_NEAR(lambda, lambdas[0], 2e-5) << "the breaks do not share one wavelength";
    EXPECT_NEAR(lambda, 39.6, 0.05);  // printed to 0.1 mm
  }
  // "Exactly 0 at u = 0 and u = lambda" (extraction §8.2): at 0 by its zero c0, at lambda to rounding.
  const auto& last = pieces[3];
  const double end = 39.6;
  EXPECT_EQ(p.value(0.0), 0.0);
  EXPECT_NEAR(last[0] + last[1] * end + last[2] * end * end, 0.0, printedRounding({last[0], last[1] * end, last[2] * end * end}));
}

TEST(Seed003AppendixD, DerivedGridOfSection13Item12) {
  // Extraction §13 item 12: C = B = 0, L = 150 (the bundled tool), App. D errors only (xtx with
  // its periodic term at u = x mod 39.6), Y = 250; TCP error relative to the one at (X, Z) =
  // (0, 0), in um, printed to 0.01 um. mtacc's exact model and the extraction's linear closed
  // form differ by second-order terms, below 0.005 um for these errors (rotations under 13",
  // arms under 1.3 m), so the tolerance is the printed rounding plus that: 0.01 um.
  const AppendixD d;
  const auto model = compile(d.machine, d.errors);
  const auto nominal = compileNominal(d.machine);
  const int X = d.machine->axisIndex("X"), Y = d.machine->axisIndex("Y"), Z = d.machine->axisIndex("Z");
  auto error = [&](double x, double y, double z) {
    std::vector<double> q(5, 0.0);
    q[static_cast<size_t>(X)] = x;
    q[static_cast<size_t>(Y)] = y;
    q[static_cast<size_t>(Z)] = z;
    return Vec6(poseError(toolInWorkpiece(model, q.data()), toolInWorkpiece(nominal, q.data())));
  };
  const Vec6 reference = error(0, 250, 0);
  struct Row {
    double x, z;
    Vec3 um;
  };
  const Row grid[] = {{0, 300, {4.79, -14.42, 9.08}},    {0, 600, {3.62, -10.45, 23.09}},   {350, 0, {-5.25, 7.26, -6.24}},
                      {350, 300, {-3.24, -10.27, 2.84}}, {350, 600, {-7.18, -9.42, 16.85}}, {700, 0, {-26.63, 8.18, -0.70}},
                      {700, 300, {-24.61, -4.96, 8.38}}, {700, 600, {-28.54, 0.28, 22.39}}};
  for (const auto& row : grid) {
    const Vec3 delta = (error(row.x, 250, row.z) - reference).head<3>() / kMicro;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(delta[k], row.um[k], 0.01) << "X=" << row.x << " Z=" << row.z << " component " << k;
  }
  // Absolute values (no reference subtracted): rotations in arcsec to 0.001", positions to 0.01 um.
  const Vec6 e = error(350, 250, 300);
  const Vec3 rotation(-4.680, -2.202, -3.521), position(-10.41, -22.16, 3.80);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(e[3 + k] / kArcsec, rotation[k], 0.001) << k;
    EXPECT_NEAR(e[k] / kMicro, position[k], 0.01) << k;
  }
  const Vec3 far = error(700, 100, 600).head<3>() / kMicro, near = error(120, 480, 40).head<3>() / kMicro;
  const Vec3 farPrinted(-27.80, -5.32, 21.53), nearPrinted(-18.61, -33.65, 8.74);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(far[k], farPrinted[k], 0.01) << k;
    EXPECT_NEAR(near[k], nearPrinted[k], 0.01) << k;
  }
}

}  // namespace
}  // namespace mtacc
