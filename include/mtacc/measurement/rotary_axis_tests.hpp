#pragma once
// The ISO 10791-6 tests around each rotary axis of a machine (the "K" tests: a rotary axis moving
// with the linear axes under tool-centre-point control, the other rotary axes still): the R-test
// with the sphere at two positions (a table axis: two places along its line, "two heights"; a head
// axis: two tool-ball extensions, "two radii"), and the ballbar in the axis's radial, tangential and
// axial directions. Each test is a run ready to simulate or to pair with measured readings, the
// plan entry that regenerates it, its instrument set-up and its program; its result is what the
// standard reports: the ranges of the R-test's radial, tangential and axial deviations, the range of
// the ballbar's length deviation. Which location errors each result sees is computed, one error at a
// time, on the machine's own kinematics (docs/conventions.md "ISO 10791-6 tests").
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

struct RotaryAxisTestOptions {
  std::vector<std::string> axes;  // empty: every commanded rotary axis
  double radius = 100.0;          // mm: a table axis's sphere (work ball) from its line
  double spread = 100.0;          // mm: the second sphere along a table axis's line, or the tool ball's extension on a head axis
  double ballbarLength = 100.0;   // mm
  int rtestPositions = 36;        // R-test: positions over the sweep (static readings)
  int ballbarPoints = 360;        // ballbar: readings over the sweep
  double feed = 1000.0;           // mm/min
};

enum class RotaryTestKind { RTest, BallbarRadial, BallbarTangential, BallbarAxial };
// "rtest", or the ballbar's direction: "radial", "tangential", "axial" (a plan's rotary mode).
const char* toString(RotaryTestKind kind);

struct RotaryAxisTest {
  std::string name;  // "C-rtest-1", "C-ballbar-radial"
  std::string axis;
  RotaryTestKind kind = RotaryTestKind::RTest;
  std::string description;
  double from = 0, to = 0;  // the sweep of the axis (rad)
  std::string planEntry;    // the plan YAML run (docs/file-formats.md "Test plans") that regenerates `run`
  MeasurementRun run;
};

struct RotaryAxisTestSet {
  std::vector<RotaryAxisTest> tests;
  std::vector<std::string> notes;  // tests not generated, and why
};
// Per axis, from a start pose with the linear axes at mid-travel (a head axis whose line passes
// through the tool: the other head axes tilted 30 deg), sweeping a full turn or the travel within
// ±90 deg. Throws InvalidInput for an axis that is not a commanded rotary axis, and
// UnreachableInput naming the test and pose for a set-up beyond the machine's travel.
RotaryAxisTestSet rotaryAxisTests(const KinematicModel& nominal, const RotaryAxisTestOptions& options);

// The standard's result of a test's readings: "radial", "tangential", "axial" ranges (R-test) or
// the "length" range (ballbar), mm.
struct RotaryTestResult {
  std::vector<std::string> quantities;
  std::vector<double> ranges;
  Eigen::VectorXd position;  // of the rotary axis at each pose (rad)
  Eigen::MatrixXd series;    // poses x quantities: the deviations whose ranges these are (mm)
};
RotaryTestResult evaluateRotaryTest(const KinematicModel& nominal, const MeasurementRun& run);

// Each location error alone, at 1 um or 1 urad: the result's ranges per unit (um per um, um per
// urad), for every test (rows: tests, then quantities; columns: parameters).
struct RotaryTestSensitivity {
  std::vector<Parameter> parameters;
  std::vector<std::vector<std::vector<double>>> perTest;  // [test][quantity][parameter]
};
RotaryTestSensitivity rotaryTestSensitivities(const KinematicModel& nominal, const std::vector<RotaryAxisTest>& tests);

// The test's program: the run's poses as G1 moves in the machine's axis positions (mm, deg) with
// `decimals` places (a controller's limit), a dwell at each R-test position; header comments with
// the set-up.
std::string rotaryTestProgram(const Machine& machine, const RotaryAxisTest& test, int decimals = 6);

}  // namespace mtacc
