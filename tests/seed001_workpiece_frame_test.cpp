// Seed 001 (Li, Sato et al., Precision Engineering 71 (2021)): the geometric error model of a
// tilting-rotary-table machine with the eight errors of Table 5 (seed lines 253-256), written
// as eq. 2 (workpiece fixed to the C table) and eqs. 10-12 (workpiece aligned with the
// machine at B = C = 0 through M_WC). The generic model, given the same errors through the
// seed-001 aliases, must equal the literal equations. Both are exact products of the same
// matrices, so they agree to rounding (1e-9 mm on coordinates of a few hundred mm).
#include <gtest/gtest.h>

#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/identification/identification.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/procedures/cubic_test.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// Table 5: identified geometric errors (um and deg).
constexpr double dxBY = 14.6e-3, dyBY = -8.9e-3, dzBY = -14.2e-3;
constexpr double alphaBY = -0.0023 * kDeg, betaBY = 0.0029 * kDeg, gammaBY = -0.00002 * kDeg;
constexpr double alphaCB = -0.00017 * kDeg, dxCB = 9.4e-3;

const char* kTable5 = R"(errors:
  δxBY: 14.6 um
  δyBY: -8.9 um
  δzBY: -14.2 um
  αBY: -0.0023 deg
  βBY: 0.0029 deg
  γBY: -0.00002 deg
  αCB: -0.00017 deg
  δxCB: 9.4 um
)";

Mat4 rx(double a) { Mat4 m = Mat4::Identity(); m.block<3, 3>(0, 0) = rotationAbout(Vec3::UnitX(), a); return m; }
Mat4 ry(double a) { Mat4 m = Mat4::Identity(); m.block<3, 3>(0, 0) = rotationAbout(Vec3::UnitY(), a); return m; }
Mat4 rz(double a) { Mat4 m = Mat4::Identity(); m.block<3, 3>(0, 0) = rotationAbout(Vec3::UnitZ(), a); return m; }
Mat4 tr(double x, double y, double z) { Mat4 m = Mat4::Identity(); m.block<3, 1>(0, 3) = Vec3(x, y, z); return m; }

// Eq. 2 without the final point: M_C M_aCB M_dxCB M_B M_gBY M_bBY M_aBY M_dBY (eqs. 3-9).
Mat4 eq2(double b, double c) {
  return rz(c) * rx(alphaCB) * tr(dxCB, 0, 0) * ry(b) * rz(gammaBY) * ry(betaBY) * rx(alphaBY) * tr(dxBY, dyBY, dzBY);
}
// Eq. 12.
Mat4 mwc() {
  return (rx(alphaCB) * tr(dxCB, 0, 0) * rz(gammaBY) * ry(betaBY) * rx(alphaBY) * tr(dxBY, dyBY, dzBY)).inverse();
}

KinematicModel modelWith(WorkpieceAlignment alignment) {
  auto machine = std::make_shared<Machine>(loadMachine("tilting-table"));
  machine->alignment = alignment;
  const auto errors = parseErrors(*machine, kTable5, "seed001-table5");
  return compile(machine, errors);
}

std::vector<std::array<double, 5>> randomPoses(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> lin(-200, 200), b(-100 * kDeg, 100 * kDeg), c(-kPi, kPi);
  std::vector<std::array<double, 5>> poses;
  for (int i = 0; i < n; ++i) poses.push_back({lin(rng), lin(rng), lin(rng), b(rng), c(rng)});
  return poses;
}

TEST(Seed001WorkpieceFrame, Table5GenericModelEqualsEq2) {
  const auto model = modelWith(WorkpieceAlignment::Table);
  for (const auto& q : randomPoses(200)) {
    const Vec3 pm(q[0], q[1], q[2]);
    const Vec3 expected = (eq2(q[3], q[4]) * pm.homogeneous()).head<3>();
    EXPECT_LT((toolPoint(model, q.data()).position - expected).norm(), 1e-9);
  }
}

TEST(Seed001WorkpieceFrame, Table5GenericModelEqualsEq10To12) {
  const auto model = modelWith(WorkpieceAlignment::Machine);
  for (const auto& q : randomPoses(200)) {
    const Vec3 pm(q[0], q[1], q[2]);
    const Vec3 expected = (mwc() * eq2(q[3], q[4]) * pm.homogeneous()).head<3>();
    EXPECT_LT((toolPoint(model, q.data()).position - expected).norm(), 1e-9);
  }
}

TEST(Seed001WorkpieceFrame, Table5AlignedWorkpieceHasNoDeviationAtBC0) {
  const auto aligned = modelWith(WorkpieceAlignment::Machine);
  const auto onTable = modelWith(WorkpieceAlignment::Table);
  for (auto q : randomPoses(50)) {
    q[3] = q[4] = 0.0;
    EXPECT_LT((toolPoint(aligned, q.data()).position - Vec3(q[0], q[1], q[2])).norm(), 1e-12);
    // Without M_WC the table frame is displaced even though B and C do not move (seed 001 §4.3).
    EXPECT_GT((toolPoint(onTable, q.data()).position - Vec3(q[0], q[1], q[2])).norm(), 1e-3);
  }
}

// §4.3 (L217): for the cubic machining test "the sensitivity coefficients alpha_BY and
// alpha_CB are the same ... delta_yBY and delta_xCB are both 0". The plan: the nine zones of
// Tables 1-2 (all cut at B = +30 deg, data/test-pieces/seed001-cubic.yaml), the height of each
// zone, workpiece aligned with M_WC (eqs. 10-12), the eight errors of Table 5 named as in the
// seed. The extraction's §7.3: rank 3 from heights (U, alphaBY + alphaCB, betaBY), 4 with the
// in-zone tilts (adding K1 = alphaBY cos B + alphaCB + gammaBY sin B).
TEST(Seed001WorkpieceFrame, CubicTestObservabilityReportsTheSeedAmbiguity) {
  const auto model = modelWith(WorkpieceAlignment::Machine);
  const auto nominal = compileNominal(model.machine);
  IdentificationProblem problem;
  problem.machine = model.machine;
  problem.start = ErrorModel::zero(*model.machine);  // first order, as the seed's sensitivities
  for (const char* n : {"dxBY", "dyBY", "dzBY", "alphaBY", "betaBY", "gammaBY", "alphaCB", "dxCB"})
    problem.parameters.push_back(findParameter(*model.machine, problem.start, n));
  problem.runs = cubicZoneRuns(nominal, seed001CubicTest(), false);
  const auto heights = planObservability(problem);
  // ISO names: dxBY = -X0B, dyBY = -Y0B, dzBY = -Z0B, alphaBY = -A0B, gammaBY = -C0B,
  // alphaCB = -A0C, dxCB = -X0C. gammaBY (C0B) has no effect on the zone heights either, which
  // the text does not say: it tilts each zone about its own centre line (extraction §8, C6).
  EXPECT_EQ(heights.noEffect, (std::vector<std::string>{"Y0B", "C0B", "X0C"}));
  ASSERT_EQ(heights.groups.size(), 2u);
  EXPECT_EQ(heights.groups[0].names, (std::vector<std::string>{"X0B", "Z0B"}));  // one uniform offset U of the tilted zones
  EXPECT_EQ(heights.groups[1].names, (std::vector<std::string>{"A0B", "A0C"}));
  ASSERT_EQ(heights.groups[1].observable.size(), 1u);
  EXPECT_NEAR(heights.groups[1].observable[0][0], 1.0, 1e-9);
  EXPECT_NEAR(heights.groups[1].observable[0][1], 1.0, 1e-9);
  EXPECT_EQ(heights.rank, 3);

  problem.runs = cubicZoneRuns(nominal, seed001CubicTest(), true);
  const auto tilts = planObservability(problem);
  EXPECT_EQ(tilts.noEffect, (std::vector<std::string>{"Y0B", "X0C"}));
  EXPECT_EQ(tilts.rank, 4);
  const auto findings = tilts.findings();
  ASSERT_EQ(findings.size(), 4u);
  // tan 15 deg = (1 - cos 30) / sin 30: the extraction's null direction (sin 15, -cos 15).
  EXPECT_EQ(findings[2], "X0B and Z0B act alike: only X0B + 0.2679 Z0B observable (lengths in mm, angles in rad)");
  ASSERT_EQ(tilts.groups.size(), 2u);
  EXPECT_EQ(tilts.groups[1].names, (std::vector<std::string>{"A0B", "C0B", "A0C"}));
  EXPECT_EQ(tilts.groups[1].observable.size(), 2u);  // K1 and K2
}

}  // namespace
}  // namespace mtacc
