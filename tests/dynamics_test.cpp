// Rigid-body dynamics against closed forms: 1- and 2-DOF oscillators, springs in series, a
// rigid body on four supports, the symmetric and antisymmetric modes of a symmetric model;
// modal superposition against the direct solve, reciprocity, the FRF at 0 Hz against the
// static compliance; the response to an axis acceleration against a hand calculation; and
// malformed models. The models are exact linear systems, so the tolerances are rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mtacc/io/structure_yaml.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "mtacc/workflows/dynamics.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// A support that holds everything except what the test studies: 1e6 N/um and N m/urad.
const char* kStiff = "1.0e6";

StructureModel model(const std::string& yaml) { return parseStructure(yaml, "test.yaml"); }

std::vector<double> sorted(const Eigen::VectorXd& v) {
  std::vector<double> s(v.data(), v.data() + v.size());
  std::sort(s.begin(), s.end());
  return s;
}

TEST(Dynamics, OneDofOscillator) {
  const auto m = model(std::string(R"(
bodies:
  - {name: mass, mass: 100, centre: [0 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
elements:
  - {type: setup, bodies: [ground, mass], point: [0 mm, 0 mm, 0 mm], stiffness: [10, )") + kStiff + ", " + kStiff + ", " +
                       kStiff + ", " + kStiff + ", " + kStiff + R"(]}
tcp: {body: mass, point: [0 mm, 0 mm, 0 mm]}
)");
  const auto mats = assembleStructure(m);
  const auto modes = undampedModes(m, mats);
  EXPECT_NEAR(modes.frequencies[0], std::sqrt(10e6 / 100) / (2 * kPi), 1e-9 * modes.frequencies[0]);
  EXPECT_NEAR(staticCompliance(mats)(0, 0), 1 / 10e6, 1e-20);
}

// The same oscillator with a damper c along x: its state-space eigenvalue has |lambda| = w_n and
// -Re(lambda) / |lambda| = c / (2 sqrt(k m)), the damping ratio `mtacc dynamics` reports.
TEST(Dynamics, DampedOneDofOscillatorHasItsClosedFormDampingRatio) {
  const double k = 10e6, mass = 100, c = 3000;  // N/m, kg, N s/m: zeta = 0.047
  const auto m = model(std::string(R"(
bodies:
  - {name: mass, mass: 100, centre: [0 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
elements:
  - {type: setup, bodies: [ground, mass], point: [0 mm, 0 mm, 0 mm], damping: [3000, 0, 0, 0, 0, 0], stiffness: [10, )") + kStiff +
                       ", " + kStiff + ", " + kStiff + ", " + kStiff + ", " + kStiff + R"(]}
tcp: {body: mass, point: [0 mm, 0 mm, 0 mm]}
)");
  const auto damped = dampedModes(assembleStructure(m));
  ASSERT_FALSE(damped.empty());
  EXPECT_NEAR(damped[0].frequency, std::sqrt(k / mass) / (2 * kPi), 1e-9 * damped[0].frequency);
  EXPECT_NEAR(damped[0].dampingRatio, c / (2 * std::sqrt(k * mass)), 1e-9);
  for (size_t i = 1; i < damped.size(); ++i) EXPECT_NEAR(damped[i].dampingRatio, 0.0, 1e-9) << i;  // the stiff directions have no damper
}

// A beam's joints take `stiffness_damping` beta as D = beta K (stiffness-proportional damping):
// on the bundled arm, 2e-5 s on each of the arm's and the ram's joints.
TEST(Dynamics, BeamJointsDampInProportionToTheirStiffness) {
  const StructureModel m = loadStructure("tzyx-arm-x");
  int joints = 0;
  for (const auto& c : m.connections) {
    if (c.type != "beam") continue;
    ++joints;
    EXPECT_LE((c.damping - 2.0e-5 * c.stiffness).norm(), 1e-12 * c.stiffness.norm()) << c.name;
  }
  EXPECT_EQ(joints, 8);  // four between the five segments of each beam
}

// ground -k1- body1 -k2- body2, along x, springs on the line of the centres.
std::string twoInSeries(double k1, double k2, const std::string& damping = "") {
  return std::string(R"(
bodies:
  - {name: one, mass: 50, centre: [0 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
  - {name: two, mass: 20, centre: [500 mm, 0 mm, 0 mm], inertia: [0.5, 0.5, 0.5, 0, 0, 0]}
elements:
  - {type: spring, bodies: [ground, one], point: [0 mm, 0 mm, 0 mm], stiffness: [)") + std::to_string(k1) + ", " + kStiff +
         ", " + kStiff + ", " + kStiff + ", " + kStiff + ", " + kStiff + "]" + damping + R"(}
  - {type: spring, bodies: [one, two], point: [500 mm, 0 mm, 0 mm], stiffness: [)" + std::to_string(k2) + ", " + kStiff +
         ", " + kStiff + ", " + kStiff + ", " + kStiff + ", " + kStiff + "]" + damping + R"(}
tcp: {body: two, point: [500 mm, 0 mm, 0 mm]}
)";
}

TEST(Dynamics, TwoDofOscillator) {
  const double k1 = 30e6, k2 = 12e6, m1 = 50, m2 = 20;
  const auto m = model(twoInSeries(30, 12));
  const auto modes = undampedModes(m, assembleStructure(m));
  // det(K - w^2 M) = 0 for K = [[k1 + k2, -k2], [-k2, k2]], M = diag(m1, m2).
  const double b = (k1 + k2) / m1 + k2 / m2, c = k1 * k2 / (m1 * m2);
  const double w1 = std::sqrt((b - std::sqrt(b * b - 4 * c)) / 2), w2 = std::sqrt((b + std::sqrt(b * b - 4 * c)) / 2);
  EXPECT_NEAR(modes.frequencies[0], w1 / (2 * kPi), 1e-9 * w1);
  EXPECT_NEAR(modes.frequencies[1], w2 / (2 * kPi), 1e-9 * w2);
}

TEST(Dynamics, SpringsInSeries) {
  const auto m = model(twoInSeries(30, 12));
  EXPECT_NEAR(staticCompliance(assembleStructure(m))(0, 0), 1 / 30e6 + 1 / 12e6, 1e-18);
}

// A plate (centre at the origin) on four supports at (+-a, +-b, 0) with translational
// stiffness only.
std::string plate(const std::string& damping) {
  std::string s = R"(
bodies:
  - {name: plate, mass: 500, centre: [0 mm, 0 mm, 0 mm], inertia: [20, 40, 55, 0, 0, 0]}
elements:
)";
  for (const char* p : {"[400 mm, 250 mm, 0 mm]", "[-400 mm, 250 mm, 0 mm]", "[400 mm, -250 mm, 0 mm]", "[-400 mm, -250 mm, 0 mm]"})
    s += std::string("  - {type: setup, bodies: [ground, plate], point: ") + p + ", stiffness: [50, 80, 200, 0, 0, 0]" +
         damping + "}\n";
  return s + "tcp: {body: plate, point: [300 mm, 200 mm, 500 mm]}\n";
}

TEST(Dynamics, RigidBodyOnFourSupports) {
  const auto m = model(plate(""));
  const auto modes = undampedModes(m, assembleStructure(m));
  const double kx = 50e6, ky = 80e6, kz = 200e6, a = 0.4, b = 0.25, mass = 500;
  std::vector<double> expected = {4 * kx / mass, 4 * ky / mass, 4 * kz / mass, 4 * kz * b * b / 20, 4 * kz * a * a / 40,
                                  4 * (kx * b * b + ky * a * a) / 55};
  for (auto& w2 : expected) w2 = std::sqrt(w2) / (2 * kPi);
  std::sort(expected.begin(), expected.end());
  const auto got = sorted(modes.frequencies);
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(got[i], expected[i], 1e-9 * expected[i]) << i;
}

TEST(Dynamics, SymmetricAndAntisymmetricModes) {
  const auto m = model(std::string(R"(
bodies:
  - {name: left, mass: 10, centre: [-1000 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
  - {name: right, mass: 10, centre: [1000 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
elements:
  - {type: spring, bodies: [ground, left], point: [-1000 mm, 0 mm, 0 mm], stiffness: [4, )") + kStiff + ", " + kStiff + ", " +
                       kStiff + ", " + kStiff + ", " + kStiff + R"(]}
  - {type: spring, bodies: [ground, right], point: [1000 mm, 0 mm, 0 mm], stiffness: [4, )" + kStiff + ", " + kStiff +
                       ", " + kStiff + ", " + kStiff + ", " + kStiff + R"(]}
  - {type: spring, bodies: [left, right], point: [1000 mm, 0 mm, 0 mm], stiffness: [1, 0, 0, 0, 0, 0]}
tcp: {body: right, point: [1000 mm, 0 mm, 0 mm]}
)");
  const auto modes = undampedModes(m, assembleStructure(m));
  const double k = 4e6, kc = 1e6, mass = 10;
  EXPECT_NEAR(modes.frequencies[0], std::sqrt(k / mass) / (2 * kPi), 1e-9 * modes.frequencies[0]);
  EXPECT_NEAR(modes.frequencies[1], std::sqrt((k + 2 * kc) / mass) / (2 * kPi), 1e-9 * modes.frequencies[1]);
  const auto& s = modes.shapes;
  EXPECT_NEAR(s(0, 0), s(6, 0), 1e-9 * std::abs(s(0, 0)));   // in phase
  EXPECT_NEAR(s(0, 1), -s(6, 1), 1e-9 * std::abs(s(0, 1)));  // opposite
}

std::vector<double> frequencies() {
  std::vector<double> f;
  for (int i = 0; i <= 200; ++i) f.push_back(i * 1.0);
  return f;
}

double largest(const Frf& h) {
  double v = 0;
  for (const auto& m : h) v = std::max(v, m.cwiseAbs().maxCoeff());
  return v;
}

TEST(Dynamics, ModalSuperpositionEqualsDirectSolveWithProportionalDamping) {
  // Damping 2e-4 s times each stiffness: D = 2e-4 K, proportional.
  const auto m = model(plate(", damping: [10000, 16000, 40000, 0, 0, 0]"));
  const auto mats = assembleStructure(m);
  const auto f = frequencies();
  const auto direct = frfDirect(mats, f), modal = frfModal(mats, undampedModes(m, mats), f);
  double worst = 0;
  for (size_t i = 0; i < f.size(); ++i) worst = std::max(worst, (direct[i] - modal[i]).cwiseAbs().maxCoeff());
  EXPECT_LE(worst / largest(direct), 1e-6);
  // The 3 x 3 is not trivial: the TCP is off the centre, so there is cross-talk.
  EXPECT_GT(std::abs(direct[0](0, 2)), 1e-3 * std::abs(direct[0](0, 0)));
}

// The FRF's default method: the modal sum only where it is exact (proportional damping), the
// direct solve where the damping couples the modes, as the bundled design's joint dampers do:
// there the modal sum's |Hxx| peak is a third below the exact one.
TEST(Dynamics, AutoMethodTakesTheModalSumOnlyForProportionalDamping) {
  const auto f = frequencies();
  const auto proportional = model(plate(", damping: [10000, 16000, 40000, 0, 0, 0]"));
  const auto pm = assembleStructure(proportional);
  EXPECT_LE(modalDampingCoupling(pm, undampedModes(proportional, pm)), 1e-9);
  const auto p = structureFrf(proportional, {{}, f});
  EXPECT_EQ(p.method, "modal");
  EXPECT_TRUE(p.warnings.empty());

  const auto design = loadStructure("tzyx-arm-x");
  const auto at = structurePositions(design, "Y=400,Z=-300", "at");
  std::vector<double> hz;
  for (int k = 1; k <= 200; ++k) hz.push_back(k);
  const auto c = structureFrf(design, {at, hz});
  EXPECT_EQ(c.method, "direct");
  EXPECT_GE(c.dampingCoupling, 0.1);
  const auto exact = frfDirect(assembleStructure(design, at), hz);
  const auto forced = structureFrf(design, {at, hz, "modal"});
  EXPECT_EQ(forced.method, "modal");
  ASSERT_EQ(forced.warnings.size(), 1u);
  EXPECT_NE(forced.warnings[0].find("not proportional"), std::string::npos);
  double peakAuto = 0, peakExact = 0, peakModal = 0;
  for (size_t i = 0; i < hz.size(); ++i) {
    peakAuto = std::max(peakAuto, std::abs(c.frf[i](0, 0)));
    peakExact = std::max(peakExact, std::abs(exact[i](0, 0)));
    peakModal = std::max(peakModal, std::abs(forced.frf[i](0, 0)));
  }
  EXPECT_DOUBLE_EQ(peakAuto, peakExact);
  EXPECT_LT(peakModal, 0.8 * peakExact);
}

TEST(Dynamics, ReciprocityAndStaticLimit) {
  const auto m = model(plate(", damping: [3000, 1000, 50000, 0, 0, 0]"));  // not proportional
  const auto mats = assembleStructure(m);
  const auto h = frfDirect(mats, frequencies());
  for (const auto& x : h) EXPECT_LE((x - x.transpose()).cwiseAbs().maxCoeff(), 1e-12 * x.cwiseAbs().maxCoeff());
  const Eigen::Matrix3d c = staticCompliance(mats);
  EXPECT_LE((h[0].real() - c).cwiseAbs().maxCoeff(), 1e-12 * c.cwiseAbs().maxCoeff());
  EXPECT_LE(h[0].imag().cwiseAbs().maxCoeff(), 1e-12 * c.cwiseAbs().maxCoeff());
}

// Body 1 (base, centre at z = -h) on a 6-DOF setup spring; body 2 (slide, centre at the origin)
// moved by X on four carriages at (+-a, +-b, -h) (stiffness normal to X) and a drive at
// (0, 0, -h). Accelerating X loads the slide's centre with -m2 a; by hand (the derivation in
// the comments): the drive stretches by -m2 a / kd, the base moves by -m2 a / k1x and tilts
// by -h m2 a / k1ry, the slide tilts further by -h m2 a / (4 kz a^2), and the TCP at height t
// above the slide's centre moves by x2 + theta2 t (and, at X, by -theta1 X vertically).
TEST(Dynamics, AccelerationResponseEqualsTheHandCalculation) {
  const auto m = model(R"(
bodies:
  - {name: base, mass: 800, centre: [0 mm, 0 mm, -150 mm], inertia: [60, 80, 90, 0, 0, 0]}
  - {name: slide, mass: 120, centre: [0 mm, 0 mm, 0 mm], inertia: [4, 5, 6, 0, 0, 0]}
elements:
  - {type: setup, bodies: [ground, base], point: [0 mm, 0 mm, -150 mm], stiffness: [400, 500, 600, 70, 90, 110]}
  - {type: guide, bodies: [base, slide], point: [200 mm, 100 mm, -150 mm], along: [1, 0, 0], up: [0, 0, 1], stiffness: [300, 250]}
  - {type: guide, bodies: [base, slide], point: [-200 mm, 100 mm, -150 mm], along: [1, 0, 0], up: [0, 0, 1], stiffness: [300, 250]}
  - {type: guide, bodies: [base, slide], point: [200 mm, -100 mm, -150 mm], along: [1, 0, 0], up: [0, 0, 1], stiffness: [300, 250]}
  - {type: guide, bodies: [base, slide], point: [-200 mm, -100 mm, -150 mm], along: [1, 0, 0], up: [0, 0, 1], stiffness: [300, 250]}
  - {type: drive, bodies: [base, slide], point: [0 mm, 0 mm, -150 mm], along: [1, 0, 0], stiffness: 150}
axes:
  - {name: X, direction: [1, 0, 0], moves: [slide], travel: [-300 mm, 300 mm]}
tcp: {body: slide, point: [0 mm, 0 mm, 250 mm]}
)");
  const double m2 = 120, g = kStandardGravity, h = 0.15, t = 0.25, a = 0.2;
  const double kd = 150e6, kz = 250e6, k1x = 400e6, k1ry = 90 / 1e-6;
  const double s = -m2 * g / kd;                 // drive stretch
  const double x1 = -m2 * g / k1x;               // base translation
  const double th1 = -h * m2 * g / k1ry;         // base tilt (drive force at h below the slide)
  const double th2 = th1 - h * m2 * g / (4 * kz * a * a);
  const double x2 = s + x1 + h * th2;            // drive point of the slide moves x2 - h theta2
  const double expected = x2 + th2 * t;
  for (double x : {0.0, 0.2}) {
    const Eigen::Matrix<double, 3, Eigen::Dynamic> r = accelerationResponse(assembleStructure(m, {x})) * g;
    EXPECT_NEAR(r(0, 0), expected, 1e-15) << "X = " << x;
    EXPECT_NEAR(r(1, 0), 0.0, 1e-15);
    // Away from X = 0 the tilted base lifts the slide: -theta1 X.
    EXPECT_NEAR(r(2, 0), -th1 * x, 1e-15) << "X = " << x;
  }
}

TEST(Dynamics, MalformedModels) {
  // A body held in x only: singular stiffness, named.
  const auto loose = model(R"(
bodies:
  - {name: loose, mass: 10, centre: [0 mm, 0 mm, 0 mm], inertia: [1, 1, 1, 0, 0, 0]}
elements:
  - {type: spring, bodies: [ground, loose], point: [0 mm, 0 mm, 0 mm], stiffness: [1, 1, 1, 0, 1, 1]}
tcp: {body: loose, point: [0 mm, 0 mm, 0 mm]}
)");
  const auto singular = test::thrown<InputError>([&] { undampedModes(loose, assembleStructure(loose)); });
  ASSERT_TRUE(singular);
  EXPECT_NE(std::string(singular->what()).find("'loose' is free to move about x"), std::string::npos) << singular->what();
  EXPECT_THROW(model("bodies:\n  - {name: b, centre: [0 mm, 0 mm, 0 mm]}\nelements: []\ntcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n"),
               InputError);
  EXPECT_THROW(model("bodies:\n  - {name: b, mass: 0, inertia: [1, 1, 1, 0, 0, 0]}\nelements: []\n"
                     "tcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n"),
               InputError);
  const auto self = test::thrown<InputError>([&] {
    model("bodies:\n  - {name: b, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\nelements:\n"
          "  - {type: spring, bodies: [b, b], point: [0 mm, 0 mm, 0 mm], stiffness: 1}\ntcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n");
  });
  ASSERT_TRUE(self);
  EXPECT_EQ(self->where().line, 4);
  EXPECT_NE(std::string(self->what()).find("cannot join a body to itself"), std::string::npos);
}

TEST(Dynamics, PrimitivesCombineByTheParallelAxisTheorem) {
  // Two 1 kg cubes of 0.1 m side, centres 0.2 m apart along x: about the common centre,
  // Jyy = 2 (m s^2/6 + m d^2) with d = 0.1 m.
  const auto b = combineParts("pair", {cuboidPart(Vec3(0.1, 0.1, 0.1), 1, Vec3(-0.1, 0, 0)),
                                       cuboidPart(Vec3(0.1, 0.1, 0.1), 1, Vec3(0.1, 0, 0))});
  EXPECT_NEAR(b.inertia(1, 1), 2 * (0.01 / 6 + 0.01), 1e-15);
  EXPECT_NEAR(b.inertia(0, 0), 2 * 0.01 / 6, 1e-15);
  const auto p = prismPart(Vec3(0.3, 0.6, 1.0), 9.0, Vec3::Zero());  // right triangle legs 0.3, 0.6
  EXPECT_NEAR(p.inertia(2, 2), 9.0 * (0.09 + 0.36) / 18, 1e-15);
  const auto c = cylinderPart({0.1, 0.0, 0.5, 2}, 4.0, Vec3::Zero());
  EXPECT_NEAR(c.inertia(2, 2), 4.0 * 0.01 / 2, 1e-15);
}

}  // namespace
}  // namespace mtacc
