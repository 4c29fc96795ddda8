// Seed 000 §3.5 (Bossoni, ETH): the linear axes' motions on the cone frustum per 5-axis family,
// in closed form, against mtacc's generic inverse kinematics on the bundled machines; the NAS 979
// cone of §2.1 and face milling. Reference: seed000_part1_cone_test_piece.md §2.6-2.8, §9.1.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "mtacc/procedures/cone.hpp"
#include "reference_values.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

ConeSpec cone(double alphaDeg, double betaDeg, double gammaDeg, double r, Vec3 centre = Vec3::Zero()) {
  ConeSpec s;
  s.alpha = alphaDeg * kDeg;
  s.beta = betaDeg * kDeg;
  s.gamma = gammaDeg * kDeg;
  s.radius = r;
  s.centre = centre;
  return s;
}

// The double pivot head with the pivot Q at distance l from the TCP (the bundled head has 200 mm).
KinematicModel doublePivotHead(double l) {
  auto machine = std::make_shared<Machine>(*test::bundled("double-pivot-head"));
  machine->toolOffset = Vec3(0, 0, -l);
  return compileNominal(machine);
}

double range(const ConeMotion& m, const std::string& name) {
  for (const auto& a : m.axes)
    if (a.axis == name) return a.range;
  throw std::runtime_error(name);
}

// 7200 points: the extremes between samples are off by r_Q (1 - cos(pi / 7200)) < 1e-7 r_Q.
ConeMotion motion(const KinematicModel& nominal, const ConeSpec& s) { return coneMotion(nominal, s, conePath(s, 7200)); }

// Table 3.3 (L2617-2668): the ranges of the linear axes of the double pivot head for r_Q = 0.5
// (unit diameter), printed as surds; eqs 3.46-3.48. Here alpha = -10 deg, r = 40 mm, l = 200 mm
// (r_Q = r - l sin(alpha) = 74.73 mm), ranges divided by 2 r_Q; tolerance 1e-4, the sampling.
TEST(Seed000LinearAxes, Table3_3DoublePivotRangesForAUnitDiameter) {
  const auto nominal = doublePivotHead(200);
  const double alpha = -10, r = 40, rq = r - 200 * std::sin(alpha * kDeg);
  struct Row {
    double beta, gamma;
    const char* printedX;
    double x;
    const char* printedY;
    double y;
    const char* printedZ;
    double z;
  };
  const double s3 = std::sqrt(3.0) / 2, s78 = std::sqrt(7.0 / 8), s23 = std::sqrt(2.0 / 3);
  const Row rows[] = {{0, 30, "1", 1, "1", 1, "0", 0},  // "any" gamma
                      {30, 0, "√3/2", s3, "1", 1, "1/2", 0.5},
                      {30, 45, "√(7/8)", s78, "√(7/8)", s78, "1/2", 0.5},
                      {30, 90, "1", 1, "√3/2", s3, "1/2", 0.5},
                      {std::atan(std::sqrt(2.0)) / kDeg, 45, "√(2/3)", s23, "√(2/3)", s23, "√(2/3)", s23},
                      {90, 0, "0", 0, "1", 1, "1", 1}};
  for (const auto& row : rows) {
    const auto m = motion(nominal, cone(alpha, row.beta, row.gamma, r));
    const std::string set = fmt::format("beta {:.1f} deg, gamma {:g} deg", row.beta, row.gamma);
    const std::array<std::tuple<const char*, const char*, double>, 3> columns{
        {{"X", row.printedX, row.x}, {"Y", row.printedY, row.y}, {"Z", row.printedZ, row.z}}};
    for (const auto& [axis, printed, value] : columns)
      test::expectReproduced({"000", "Table 3.3, L2617-2668", fmt::format("range of {} at {} (printed {})", axis, set, printed), value, 4, ""},
                             range(m, axis) / (2 * rq), 1e-4, "the sampling of the path");
  }
  // The last two rows print one angle each (90 deg, 45 deg); the other is lost.
  const std::array<std::pair<const char*, double>, 6> lost{
      {{"X", 1}, {"Y", 0}, {"Z", 1}, {"X", 1 / std::sqrt(2.0)}, {"Y", 1 / std::sqrt(2.0)}, {"Z", 1}}};
  for (size_t k = 0; k < lost.size(); ++k)
    test::recordNotComputed({"000", "Table 3.3, L2617-2668", fmt::format("range of {} in row {} (an angle lost)", lost[k].first, 7 + k / 3),
                             lost[k].second, 4, ""},
                            "one of the row's two angles is lost in the text (L2663, L2665); the reference reconstructs it from "
                            "these very ranges, so computing them back would be circular");
}

// Table 3.2 (L2519-2537): r_Q against r as the pivot distance l varies against s = r / sin(alpha)
// (eq. 3.17), read from the generic inverse kinematics as r_Q = dZ / (2 sin(beta)) (eq. 3.46) at
// beta 30, gamma 0. The second block is printed "90-180 deg" and means negative alpha (erratum,
// reference §2.6).
TEST(Seed000LinearAxes, Table3_2PivotCircleAgainstThePathRadius) {
  struct Row {
    int line;
    double alpha, l, r;
    const char* condition;
    const char* printed;
    bool (*holds)(double rq, double r);
  };
  const Row rows[] = {
      {2524, 30, 200, 100, "0 < alpha < 90 deg, l = s", "r_Q = 0", [](double rq, double) { return rq < 1e-9; }},
      {2526, 30, 200, 150, "0 < alpha < 90 deg, l < 2s", "r_Q < r", [](double rq, double r) { return rq < r - 1; }},
      {2528, 30, 200, 40, "0 < alpha < 90 deg, l > 2s", "r_Q > r", [](double rq, double r) { return rq > r + 1; }},
      {2530, 30, 200, 50, "0 < alpha < 90 deg, l = 2s", "r_Q = r", [](double rq, double r) { return std::abs(rq - r) < 1e-6; }},
      {2532, 30, 0, 40, "0 < alpha < 90 deg, l = 0", "r_Q = r", [](double rq, double r) { return std::abs(rq - r) < 1e-6; }},
      {2534, -30, 200, 40, "negative alpha, l > 0", "r_Q > r", [](double rq, double r) { return rq > r + 1; }},
      {2536, -30, 200, 100, "negative alpha, l = s", "r_Q = 2r", [](double rq, double r) { return std::abs(rq - 2 * r) < 1e-6; }}};
  for (const auto& row : rows) {
    const auto m = motion(doublePivotHead(row.l), cone(row.alpha, 30, 0, row.r));
    const double rq = range(m, "Z") / (2 * std::sin(30 * kDeg));
    const test::Statement statement{"000", fmt::format("Table 3.2, L{}", row.line),
                                    fmt::format("pivot circle for {} (alpha {:g} deg, l {:g}, r {:g} mm)", row.condition, row.alpha, row.l, row.r),
                                    row.printed};
    test::expectStatementHolds(statement, row.holds(rq, row.r), fmt::format("|r_Q| = {:.6f} mm", rq), "the generic inverse kinematics");
  }
}

// §3.5.2 (L2670-2800), the swivel head over a rotary table at its §3.6.3 set-up (alpha 45, beta
// 30, gamma 0, r 40, x0 = r_table - r cos(beta) with r_table 100, eq. 3.60), l = 150 mm: the
// ranges of eqs 3.46 (Z), 3.53 with 3.54 (Y = 2 r_A) and 3.59 (X between top and bottom, which
// eq. 3.60's placement makes the extremes), for alpha > beta. The thesis prints the formulas,
// not numbers: they are evaluated here and compared with the generic inverse kinematics.
TEST(Seed000LinearAxes, SwivelHeadRangesOfEqs3_46_3_53_3_59) {
  const auto s = *conePreset("swivel-head");
  const auto m = motion(compileNominal(test::bundled("swivel-head-table")), s);
  const double l = 150, r = s.radius, x0 = s.centre.x(), sa = std::sin(s.alpha), ca = std::cos(s.alpha), sb = std::sin(s.beta);
  const double rq = r - l * sa;
  EXPECT_NEAR(range(m, "Z"), 2 * std::abs(rq) * sb, 1e-6);             // eq. 3.46
  EXPECT_NEAR(range(m, "Y"), 2 * (x0 + r * ca / sa * sb), 1e-4);       // eqs 3.53-3.54, h = r cot(alpha)
  EXPECT_NEAR(range(m, "X"), 2 * (x0 + l * ca * sb), 1e-4);            // eq. 3.59
  EXPECT_NEAR(range(m, "B") / kDeg, 2 * s.beta / kDeg, 1e-6);          // Table 3.1, alpha > beta
  EXPECT_NEAR(range(m, "C") / kDeg, 360.0, 0.1);
}

// Face milling (L846-851): the tool along the surface normal, which makes the angle 90 deg - alpha
// with the cone axis, so the rotary ranges are Table 3.1's for alpha' = 90 deg - alpha: alpha 30,
// beta 30 is the singular case alpha = beta for end milling and alpha' = 60 > beta for face
// milling (B from 30 to 90 deg, C a full turn).
TEST(Seed000LinearAxes, FaceMillingTiltsByTheComplementOfAlpha) {
  auto s = cone(30, 20, 0, 40, Vec3(-65, 0, 150));
  s.faceMilling = true;
  const auto m = motion(compileNominal(test::bundled("tilting-table")), s);
  EXPECT_NEAR(range(m, "B") / kDeg, 2 * 20.0, 1e-6);  // alpha' > beta: dB = 2 beta
  EXPECT_NEAR(range(m, "C") / kDeg, 360.0, 0.1);
  double smallest = 1e9, largest = 0;
  for (Eigen::Index i = 0; i < m.q.rows(); ++i) {
    smallest = std::min(smallest, std::abs(m.q(i, 3)) / kDeg);
    largest = std::max(largest, std::abs(m.q(i, 3)) / kDeg);
  }
  EXPECT_NEAR(smallest, 60 - 20, 1e-3);  // alpha' - beta
  EXPECT_NEAR(largest, 60 + 20, 1e-3);   // alpha' + beta
}

// NAS 979 (§2.1, L694-703): "profile mill the frustum of a 10 inch diameter cone with an apex
// angle of 30 degrees. The Z axis shall rise 1.000 inch min. while traversing 180 deg". The
// preset is built from these, so its path gives them back: input echoed.
TEST(Seed000LinearAxes, Nas979PresetGivesBackItsDefinition) {
  const auto s = *conePreset("nas979");
  const auto p = conePath(s, 7200);
  double lowest = 1e9, highest = -1e9, widest = 0, apex = 0;
  for (size_t i = 0; i < p.points.size(); ++i) {
    lowest = std::min(lowest, p.points[i].z());
    highest = std::max(highest, p.points[i].z());
    widest = std::max(widest, (p.points[i] - p.points[(i + p.points.size() / 2) % p.points.size()]).norm());
  }
  const Vec3 axis = rotationAbout(Vec3::UnitY(), s.beta) * Vec3::UnitZ();
  apex = 2 * std::acos(std::abs(p.tools[0].dot(axis))) / kDeg;
  const char* where = "Section 2.1 (NAS 979), L694-703";
  test::expectInputEchoed({"000", where, "cone diameter, 10 inch", 254.0, 1, "mm"}, widest, 1e-6, "the preset's radius 127 mm");
  test::expectInputEchoed({"000", where, "apex angle", 30.0, 0, "deg"}, apex, 1e-9, "the preset's alpha 15 deg");
  test::expectInputEchoed({"000", where, "rise of the path over 180 deg, 1.000 inch", 25.4, 1, "mm"}, highest - lowest, 1e-6,
                          "the preset's beta = asin(0.1)");
}

}  // namespace
}  // namespace mtacc
