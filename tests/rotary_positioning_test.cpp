// A rotary axis's correction of its own command (issue 45, item 3): on machines whose only errors
// are the rotary axes' own angular positioning (a zero offset, a periodic error, a reversal), the
// corrected commands put the tool where the nominal machine puts it, position and direction,
// standing and moving each way; errors of other kinds are not taken for the axis's.
#include <gtest/gtest.h>

#include <numbers>

#include "mtacc/compensation/rotary_positioning.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {
namespace {

// The largest pose error (mm, and rad times 100 mm) with each rotary command corrected by its table,
// the axis moving `direction`, over poses across the rotary axes' travel.
double leftWithCorrections(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, int direction) {
  const std::vector<double> pose(static_cast<size_t>(machine->commandedCount()), 0.0);
  const auto tables = rotaryPositioning(machine, errors, pose);
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  double largest = 0.0;
  for (double a : {-1.7, -0.61, 0.0, 0.43, 1.3})
    for (double b : {-2.9, -1.0, 0.37, 2.2, 5.9}) {
      std::vector<double> q = pose, corrected;
      q[static_cast<size_t>(tables[0].axis)] = a;
      q[static_cast<size_t>(tables[1].axis)] = b;
      corrected = q;
      std::vector<int> dir(q.size(), 0);
      for (const auto& t : tables) {
        const auto k = static_cast<size_t>(t.axis);
        dir[k] = direction;
        // Standing the table's own interpolation; moving, the direction's column at the nearest position.
        if (direction == 0) {
          corrected[k] += t.correction(q[k]);
        } else {
          const auto& column = direction > 0 ? t.forward : t.reverse;
          const double u = std::clamp((q[k] - t.positions.front()) / (t.positions[1] - t.positions.front()), 0.0,
                                      static_cast<double>(t.positions.size() - 1));
          corrected[k] += column[static_cast<size_t>(std::lround(u))];
          corrected[k] += t.correction(q[k]) - t.standing[static_cast<size_t>(std::lround(u))];
        }
      }
      const Vec6 e = poseError(toolInWorkpiece(actual, corrected.data(), dir.data()), toolInWorkpiece(nominal, q.data()));
      largest = std::max({largest, e.head<3>().norm(), 100.0 * e.tail<3>().norm()});
    }
  return largest;
}

TEST(RotaryPositioning, OwnAngularErrorsAreCorrectedOnEachKindOfMachine) {
  // Tables (tilting table, B on C), heads (double pivot, C carrying B), and one of each (swivel head).
  for (const char* name : {"tilting-table", "double-pivot-head", "swivel-head-table"}) {
    SCOPED_TRACE(name);
    const auto setup = loadMachineSetup({name, "", "", std::nullopt, ""});
    const ErrorModel own = parseErrors(*setup.machine,
                                       "errors:\n  B.zero: 30 urad\n  C.zero: -20 urad\n"
                                       "  EBB: {harmonics: {period: 360 deg, terms: [{order: 1, amplitude: 8 urad}]}, reversal: 6 urad}\n"
                                       "  ECC: {harmonics: {period: 360 deg, terms: [{order: 2, amplitude: 12 urad, phase: 30 deg}]}}\n",
                                       "own.yaml");
    const std::vector<double> pose(static_cast<size_t>(setup.machine->commandedCount()), 0.0);
    const KinematicModel actual = compile(setup.machine, own), nominal = compileNominal(setup.machine);
    // Uncorrected the errors move the tool by micrometres; corrected, the interpolation between
    // positions 2 degrees apart leaves 12 urad x (2 pi / 180)^2 / 8 x 2^2 of the harmonic, far below 1 nm at 100 mm.
    EXPECT_GT(poseError(toolInWorkpiece(actual, pose.data()), toolInWorkpiece(nominal, pose.data())).tail<3>().norm(), 1e-5);
    for (int direction : {0, 1, -1}) EXPECT_LT(leftWithCorrections(setup.machine, own, direction), 2e-6) << direction;
  }
}

// C's line tilted about X turns the workpiece about neither B's line (Y) nor its own: no correction.
// Turned about Y (B0C), it turns the workpiece about B's line: B's zero offset in effect, corrected so.
TEST(RotaryPositioning, ATiltOfTheLineIsNotTheAxisOwn) {
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const std::vector<double> pose(static_cast<size_t>(setup.machine->commandedCount()), 0.0);
  for (const auto& t : rotaryPositioning(setup.machine, parseErrors(*setup.machine, "errors: {A0C: 40 urad}\n", "tilt.yaml"), pose))
    for (double c : t.standing) EXPECT_LT(std::abs(c), 1e-9);  // second order only
  const auto aboutY = rotaryPositioning(setup.machine, parseErrors(*setup.machine, "errors: {B0C: -25 urad}\n", "b0c.yaml"), pose);
  // B is on the table: its zero offset turns the table the other way (docs/conventions.md), hence +25.
  const auto zero = rotaryPositioning(setup.machine, parseErrors(*setup.machine, "errors: {B.zero: 25 urad}\n", "zero.yaml"), pose);
  for (size_t k = 0; k < aboutY.size(); ++k)
    for (size_t n = 0; n < aboutY[k].standing.size(); ++n) EXPECT_NEAR(aboutY[k].standing[n], zero[k].standing[n], 1e-12);
  EXPECT_GT(std::abs(aboutY[0].standing[0]) + std::abs(aboutY[1].standing[0]), 2e-5);
}

TEST(RotaryPositioning, AContinuousAxisRepeatsOverTheTurn) {
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const ErrorModel own = parseErrors(*setup.machine, "errors: {ECC: {harmonics: {period: 360 deg, terms: [{order: 3, amplitude: 10 urad}]}}}\n", "c.yaml");
  const std::vector<double> pose(static_cast<size_t>(setup.machine->commandedCount()), 0.0);
  const auto tables = rotaryPositioning(setup.machine, own, pose);
  const auto c = std::find_if(tables.begin(), tables.end(), [&](const auto& t) { return setup.machine->axes[static_cast<size_t>(t.axis)].name == "C"; });
  ASSERT_NE(c, tables.end());
  EXPECT_TRUE(c->modulo);
  EXPECT_EQ(c->positions.size(), 181u);
  EXPECT_NEAR(c->correction(0.3 + 2.0 * std::numbers::pi), c->correction(0.3), 1e-15);
  EXPECT_NEAR(c->correction(-0.3), c->correction(2.0 * std::numbers::pi - 0.3), 1e-15);
}

}  // namespace
}  // namespace mtacc
