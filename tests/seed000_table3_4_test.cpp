// Seed 000 Table 3.4 (L4028-4067): the equivalent cone form error caused by each single
// error on the proposed tilting-table set-up (alpha 45, beta 30, r 40, centre (-65, 0, 150)).
// The 18 entries that the reference (seed000_part1_cone_test_piece.md §5) reproduces from the
// thesis' text, with its conventions, which are mtacc's (docs/conventions.md):
//  * linear-axis squareness tilts the direction of travel; rotary location errors move the
//    axis line with everything it carries;
//  * "lin over dX_M": value * q / range of that axis on the path; "1h over dX_M": eq. 3.63, a
//    half wave cos(pi (q - mid) / range) over the path's range (eq. 3.65 for EXY: minus the
//    amplitude); ECC lin over dC = 360 deg;
//  * hysteresis: reversal of full width 10 um (+-5 um); EBBhyst "50 um/m" reproduces only as
//    +-50 urad (reference erratum 12), i.e. a reversal of width 100 urad.
// The thesis prints one decimal; the tolerance is +-0.1 um as the reference states, except
// for the hysteresis entries, which depend on the sampling (below) and are held to the
// printed digit (+-0.05 um) at 720 points.
// All 31 entries are tested: 19 reproduced, 12 in KnownDifferences with the reason and
// today's value pinned, so that a change in either direction is noticed; EYC2h is reproduced
// besides under the axis-shift convention (AxisShiftConvention).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Core>
#include <array>
#include <map>
#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/procedures/cone.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

class Seed000Table3_4 : public ::testing::Test {
 protected:
  void SetUp() override {
    machine = std::make_shared<Machine>(loadMachine("tilting-table"));
    nominal = compileNominal(machine);
    path = conePath(spec, 3600);
    motion = coneMotion(nominal, spec, path);
    for (const auto& a : motion.axes) {
      lo[a.axis] = a.min;
      range[a.axis] = a.range;
    }
  }
  // Form error (um) of a single error given as errors-file YAML.
  double formError(const std::string& yaml, bool exact = true) {
    const auto errors = parseErrors(*machine, "errors:\n  " + yaml + "\n", "table3.4");
    const auto actual = compile(machine, errors);
    return 1e3 * (exact ? coneFormErrorExact(actual, spec, path, motion) : coneFormErrorFirstOrder(actual, nominal, path, motion)).formError;
  }
  // One entry: the error given as YAML, labelled as the thesis' row.
  void reproduced(int line, const std::string& label, const std::string& yaml, double printed, double tolerance = 0.1,
                  const char* why = "the printed digit, as the reference states") {
    test::expectReproduced({"000", fmt::format("Table 3.4, L{}", line), label, printed, 1, "um"}, formError(yaml), tolerance, why);
  }
  std::string linear(const char* name, const char* axis, const char* value) {
    return fmt::format("{}: {{linear: {{value: {}, over: {} mm}}}}", name, value, range[axis]);
  }
  // 10 um * cos(pi (q - q_min - dq/2) / dq) (+ constant), eqs. 3.63 and 3.65.
  std::string halfWave(const char* name, const char* axis, const char* constant = "0 um") {
    return fmt::format("{}: {{harmonics: {{period: {} mm, zero: {} mm, terms: [{{order: 1, amplitude: 10 um}}]}}, constant: {}}}",
                       name, 2 * range[axis], lo[axis] + range[axis] / 2, constant);
  }

  ConeSpec spec;  // the defaults are the proposed set-up
  std::shared_ptr<Machine> machine;
  KinematicModel nominal;
  ConePath path;
  ConeMotion motion;
  std::map<std::string, double> lo, range;
};

TEST_F(Seed000Table3_4, LocationErrors) {
  reproduced(4034, "C0Y 30 urad", "C0Y: 30 urad", 1.0);
  reproduced(4035, "A0Z 30 urad", "A0Z: 30 urad", 3.5);
  reproduced(4036, "B0Z 30 urad", "B0Z: 30 urad", 1.0);
  reproduced(4037, "A0B 30 urad", "A0B: 30 urad", 3.5);
  reproduced(4038, "A0C 30 urad", "A0C: 30 urad", 2.0);
  reproduced(4039, "B0C 30 urad", "B0C: 30 urad", 1.0);
  reproduced(4040, "X0B 10 um", "X0B: 10 um", 3.3);
  reproduced(4041, "Y0Y 10 um", "Y0Y: 10 um", 5.8);
}

// A reversal is a step; after the harmonic removal its peak-to-valley depends on how close
// the samples fall to the reversal, so these entries depend on the number of points, which
// the thesis does not state: at 3600 points EXX gives 9.98 (printed 9.9) and EYY 10.06; at
// 720 points (what mtacc's cone Monte Carlo uses) all three print as the thesis does.
TEST_F(Seed000Table3_4, Hysteresis) {
  path = conePath(spec, 720);
  motion = coneMotion(nominal, spec, path);
  const char* why = "the printed digit at 720 points; the value depends on the sampling";
  reproduced(4044, "EXX hysteresis 10 um", "EXX: {reversal: 10 um}", 9.9, 0.05, why);   // 9.909
  reproduced(4045, "EYY hysteresis 10 um", "EYY: {reversal: 10 um}", 10.0, 0.05, why);  // 10.049
  // "50 um/m" reproduces only as +-50 urad (reference erratum 12).
  reproduced(4046, "EBB hysteresis 50 urad", "EBB: {reversal: 100 urad}", 13.3, 0.05, why);  // 13.308
}

TEST_F(Seed000Table3_4, LinearErrors) {
  reproduced(4047, "EXX linear 10 um over dX", linear("EXX", "X", "10 um"), 2.0);
  reproduced(4048, "EYY linear 10 um over dY", linear("EYY", "Y", "10 um"), 4.0);
  reproduced(4050, "ECC linear 50 urad over 360 deg", "ECC: {linear: {value: 50 urad, over: 360 deg}}", 0.7);
}

TEST_F(Seed000Table3_4, HarmonicErrors) {
  reproduced(4052, "EYX half wave 10 um over dX", halfWave("EYX", "X"), 8.1);
  // Eq. 3.65 subtracts the amplitude: (cos(...) - 1), which matters because n_x varies.
  reproduced(4053, "EXY half wave 10 um over dY", halfWave("EXY", "Y", "-10 um"), 8.4);
  reproduced(4054, "EXZ half wave 10 um over dZ", halfWave("EXZ", "Z"), 8.1);
  reproduced(4055, "EYZ half wave 10 um over dZ", halfWave("EYZ", "Z"), 3.9);
  reproduced(4066, "EZC first harmonic 10 um", "EZC: {harmonics: {period: 360 deg, zero: 0 deg, terms: [{order: 1, amplitude: 10 um}]}}", 1.2);
}

// The 12 entries mtacc does not reproduce (reference §5, which found the same values with an
// independent first-order model), each pinned at today's value to +-0.005 um.
TEST_F(Seed000Table3_4, KnownDifferences) {
  struct Entry {
    int line;
    std::string label, yaml;
    double printed, today;
    const char* reason;
  };
  const char* origin = "tilt of a linear axis: the lever arms need the origin of the machine frame, which the thesis does not give";
  const char* rotary = "error motion of a rotary axis: the frame, phase and sign conventions are not given (reference section 3, item 13)";
  auto harmonic = [&](const char* name, double period, int order, const char* amplitude) {
    return fmt::format("{}: {{harmonics: {{period: {} deg, zero: 0 deg, terms: [{{order: {}, amplitude: {}}}]}}}}", name, period,
                       order, amplitude);
  };
  const double b = range["B"] / kDeg;
  const std::vector<Entry> entries = {
      {4042, "X0C 10 um", "X0C: 10 um", 3.3, 2.763,
       "a translation of the C axis carried by B; 3.3 only if X0C acted as a constant machine-X offset like X0B"},
      {4049, "EBB linear 50 urad over dB", fmt::format("EBB: {{linear: {{value: 50 urad, over: {} deg}}}}", b), 0.6, 2.256,
       "no zero of the linear B error gives less than 2.2 um; the thesis' EBBlin convention is not stated"},
      {4056, "EAX linear 30 urad over dX", linear("EAX", "X", "30 urad"), 0.8, 1.398, origin},
      {4057, "EBY linear 30 urad over dY", linear("EBY", "Y", "30 urad"), 5.7, 2.042, origin},
      {4058, "EBX linear 30 urad over dX", linear("EBX", "X", "30 urad"), 2.8, 1.808, origin},
      {4059, "ECX linear 30 urad over dX", linear("ECX", "X", "30 urad"), 0.9, 1.984, origin},
      {4060, "EAY linear 30 urad over dY", linear("EAY", "Y", "30 urad"), 4.2, 1.240, origin},
      {4062, "EXB second harmonic 10 um", harmonic("EXB", b, 2, "10 um"), 9.8, 20.514, rotary},
      {4063, "EXC second harmonic 10 um", harmonic("EXC", 360, 2, "10 um"), 11.1, 16.231, rotary},
      {4064, "EYC second harmonic 10 um", harmonic("EYC", 360, 2, "10 um"), 16.7, 8.712,
       "ISO's translation convention; the axis-shift convention reproduces it (AxisShiftConvention)"},
      {4065, "EYB first harmonic 10 um", harmonic("EYB", b, 1, "10 um"), 8.6, 14.899, rotary},
      {4067, "EAB first harmonic 30 urad", harmonic("EAB", b, 1, "30 urad"), 5.7, 3.846, rotary},
  };
  for (const auto& e : entries)
    test::expectKnownDifference({"000", fmt::format("Table 3.4, L{}", e.line), e.label, e.printed, 1, "um"}, formError(e.yaml),
                                e.today, 0.005, e.reason);
}

// The nominal machine with the machine frame's origin at o: the linear axes' frames start there
// at home, so their angular errors turn what they carry about o (plus their own travel). The
// element after the last linear axis of each chain is set back by o, so nothing nominal moves.
std::shared_ptr<Machine> withMachineOrigin(const Machine& base, const Vec3& o) {
  auto m = std::make_shared<Machine>(base);
  for (const auto* chain : {&m->toolChain, &m->workpieceChain}) {
    m->axes[static_cast<size_t>(chain->front())].offset += o;
    size_t k = 0;
    while (k < chain->size() && !m->axes[static_cast<size_t>((*chain)[k])].isRotary()) ++k;
    if (k < chain->size()) m->axes[static_cast<size_t>((*chain)[k])].offset -= o;
    else if (chain == &m->toolChain) m->toolOffset -= o;
    else m->workpieceOffset -= o;
  }
  return m;
}

// The five tilts of linear axes (L4056-4060) depend on the lever arms, so on the machine frame's
// origin, which the thesis does not give: fitted here (three coordinates against five printed
// values) by a grid search refined tenfold twice, on the first-order deviation, which is affine
// in the origin (checked). The outcome is recorded either way: a fit within the printed digit for
// all five would support the conventions; what is left over measures how far they are off.
TEST_F(Seed000Table3_4, LinearAxisTiltsWithTheMachineOriginFitted) {
  const ConePath coarse = conePath(spec, 720);
  const ConeMotion coarseMotion = coneMotion(nominal, spec, coarse);
  struct Tilt {
    int line;
    const char* name;
    const char* axis;
    double printed, today;
  };
  const Tilt tilts[] = {{4056, "EAX", "X", 0.8, 1.278}, {4057, "EBY", "Y", 5.7, 4.943}, {4058, "EBX", "X", 2.8, 3.366},
                        {4059, "ECX", "X", 0.9, 0.966}, {4060, "EAY", "Y", 4.2, 4.421}};
  // Each tilt's deviation (um) as d0 + D o, o in mm.
  std::vector<Eigen::VectorXd> d0;
  std::vector<Eigen::MatrixXd> d;
  auto deviation = [&](const Tilt& t, const Vec3& o) -> Eigen::VectorXd {
    auto m = withMachineOrigin(*machine, o);
    const auto errors = parseErrors(*m, "errors:\n  " + linear(t.name, t.axis, "30 urad") + "\n", "tilt");
    const auto r = coneFormErrorFirstOrder(compile(m, errors), compileNominal(m), coarse, coarseMotion).deviation;
    return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())) * 1e3;
  };
  const Vec3 probe(37, -52, 81);
  std::mt19937_64 rng(5);
  const auto moved = compileNominal(withMachineOrigin(*machine, probe));
  for (int p = 0; p < 10; ++p) {
    const auto q = test::randomPose(*machine, rng);
    ASSERT_LT(poseError(toolInWorkpiece(moved, q.data()), toolInWorkpiece(nominal, q.data())).norm(), 1e-9) << "the origin moved the nominal machine";
  }
  for (const auto& t : tilts) {
    d0.push_back(deviation(t, Vec3::Zero()));
    Eigen::MatrixXd slope(d0.back().size(), 3);
    for (int i = 0; i < 3; ++i) slope.col(i) = (deviation(t, 100 * Vec3::Unit(i)) - d0.back()) / 100;
    d.push_back(slope);
    ASSERT_LT((d0.back() + slope * probe - deviation(t, probe)).cwiseAbs().maxCoeff(), 1e-9) << t.name << ": not affine in the origin";
  }
  auto formErrors = [&](const Vec3& o) {
    std::array<double, 5> pv;
    for (size_t k = 0; k < 5; ++k) {
      const Eigen::VectorXd e = d0[k] + d[k] * o;
      pv[k] = e.maxCoeff() - e.minCoeff();
    }
    return pv;
  };
  auto misfit = [&](const Vec3& o) {
    const auto pv = formErrors(o);
    double sum = 0;
    for (size_t k = 0; k < 5; ++k) sum += (pv[k] - tilts[k].printed) * (pv[k] - tilts[k].printed);
    return sum;
  };
  Vec3 best = Vec3::Zero();
  double bestMisfit = misfit(best);
  for (const double step : {100.0, 10.0, 1.0}) {
    const Vec3 centre = best;
    for (int i = -10; i <= 10; ++i)
      for (int j = -10; j <= 10; ++j)
        for (int k = -10; k <= 10; ++k) {
          const Vec3 o = centre + step * Vec3(i, j, k);
          if (const double m = misfit(o); m < bestMisfit) {
            best = o;
            bestMisfit = m;
          }
        }
  }
  const auto pv = formErrors(best);
  const std::string origin = fmt::format("the best machine origin, ({:.0f}, {:.0f}, {:.0f}) mm from the B/C pivot, fits 3 coordinates to 5 values", best.x(),
                                         best.y(), best.z());
  // A fit reproduces the table only if all five come within the printed digit.
  bool allWithin = true;
  for (size_t k = 0; k < 5; ++k) allWithin = allWithin && std::abs(pv[k] - tilts[k].printed) <= 0.1;
  for (size_t k = 0; k < 5; ++k) {
    const auto& t = tilts[k];
    const test::Printed p{"000", fmt::format("Table 3.4, L{}", t.line), fmt::format("{} linear 30 urad, machine origin fitted", t.name), t.printed, 1, "um"};
    if (allWithin)
      test::expectReproduced(p, pv[k], 0.1, origin + " (a fit: 2 degrees of freedom left)");
    else
      test::expectKnownDifference(p, pv[k], t.today, 0.005, origin + ", and leaves these beyond the printed digit");
  }
}

// The rotary error motions read as shifts of the axis line, the convention the reference found
// for EYC2h (§5: R_tilt (I - R_table) t gives 16.66), offered as "convention: axis-shift"
// (docs/file-formats.md, errors/axis_shift.hpp). EYC2h is reproduced to the printed digit (as
// the reference's 16.66); EXB2h, 20.5 as a translation, comes to 10.25 as a shift against the
// printed 9.8, still more than the digit away.
TEST_F(Seed000Table3_4, AxisShiftConvention) {
  const double b = range["B"] / kDeg;
  auto shifted = [&](const char* name, double period) {
    return fmt::format("{}: {{harmonics: {{period: {} deg, zero: 0 deg, terms: [{{order: 2, amplitude: 10 um}}]}}, convention: axis-shift}}", name,
                       period);
  };
  reproduced(4064, "EYC second harmonic 10 um, axis-shift convention", shifted("EYC", 360), 16.7, 0.05, "the printed digit");
  test::expectKnownDifference({"000", "Table 3.4, L4062", "EXB second harmonic 10 um, axis-shift convention", 9.8, 1, "um"},
                              formError(shifted("EXB", b)), 10.246, 0.005,
                              "no convention found: a translation gives 20.5, an axis shift 10.25 (reference section 5)");
}

// §3.10.4 (L3906-3950): typical form-error types.
TEST_F(Seed000Table3_4, FormErrorTypes) {
  auto type = [&](const std::string& yaml) {
    const auto errors = parseErrors(*machine, "errors:\n  " + yaml + "\n", "types");
    return formErrorType(coneFormErrorExact(compile(machine, errors), spec, path, motion).deviation);
  };
  const std::vector<std::string> topBottom{"B0Z: 30 urad", "B0C: 30 urad", "X0B: 10 um", linear("EXX", "X", "10 um"),
                                           linear("EYY", "Y", "10 um"), "ECC: {linear: {value: 50 urad, over: 360 deg}}"};
  for (const auto& e : topBottom)
    EXPECT_EQ(type(e), FormErrorType::TopBottom) << e;
  for (const std::string e : {"C0Y: 30 urad", "A0Z: 30 urad", "A0B: 30 urad", "A0C: 30 urad", "Y0Y: 10 um"})
    EXPECT_EQ(type(e), FormErrorType::Asymmetric) << e;
}

TEST_F(Seed000Table3_4, FirstOrderAgreesWithExact) {
  for (const std::string e : {"A0Z: 30 urad", "X0B: 10 um", "EYY: {reversal: 10 um}", "ECC: {linear: {value: 50 urad, over: 360 deg}}"}) {
    const double exact = formError(e, true), first = formError(e, false);
    EXPECT_NEAR(exact, first, 0.01 * exact) << e;
  }
}

}  // namespace
}  // namespace mtacc
