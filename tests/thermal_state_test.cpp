// The errors at a thermal state (issue 19): the scale expansion as the X axis's positioning
// error, exact against scaleExpansion, in the kinematics, and in the compensation tables written
// cold and warm.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/errors/thermal_state.hpp"
#include "mtacc/io/thermal_state_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/compensation.hpp"
#include "mtacc/workflows/machine_setup.hpp"
#include "test_helpers.hpp"
#include "test_paths.hpp"

namespace mtacc {
namespace {

// Three sensors along X's scale (at its ends and past the middle) of the 3-axis machine, whose
// X moves the table; the drift was measured at X = 100 mm.
ScaleState warmX(const Machine& machine, std::vector<double> temperatures) {
  const int x = machine.axisIndex("X");
  const auto& travel = *machine.axes[static_cast<size_t>(x)].travel;
  return {x, {{travel.min, 0.5 * (travel.min + travel.max) + 37.0, travel.max}, 11.5e-6, 100.0, 20.0}, std::move(temperatures)};
}

TEST(ThermalState, TheExpansionTermIsTheScaleExpansionAlongTheWholeTravel) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto scale = warmX(*machine, {21.5, 26.0, 22.0});
  const auto& travel = *machine->axes[static_cast<size_t>(scale.axis)].travel;
  const auto term = scaleExpansionTerm(scale.sensors, scale.temperatures, travel.min, travel.max);
  double largest = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double x = travel.min + (travel.max - travel.min) * i / 1000.0;
    EXPECT_NEAR(term.value(x), scaleExpansion(scale.sensors, scale.temperatures, x), 1e-12) << x;
    largest = std::max(largest, std::fabs(term.value(x)));
  }
  EXPECT_GT(largest, 5e-3) << "micrometres of expansion, as a warm scale gives";
  EXPECT_NEAR(term.value(100.0), 0.0, 1e-15) << "zero at the reference position";
}

TEST(ThermalState, TheWarmMachineGoesTheExpansionBeyondItsCommand) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto cold = ErrorModel::zero(*machine);
  const auto scale = warmX(*machine, {21.5, 26.0, 22.0});
  const auto warm = atThermalState(*machine, cold, {{scale}, std::nullopt});
  const auto coldModel = compile(machine, cold), warmModel = compile(machine, warm);
  for (double x : {0.0, 13.0, 150.0, 337.0, 600.0}) {
    const std::vector<double> q{x, 40.0, -100.0};
    const Vec3 moved = toolPoint(warmModel, q.data()).position - toolPoint(coldModel, q.data()).position;
    const Vec3 expected = scaleExpansion(scale.sensors, scale.temperatures, x) * machine->axes[static_cast<size_t>(scale.axis)].direction;
    EXPECT_LT((moved - expected).norm(), 1e-12) << x << " moved " << moved.transpose() << " expected " << expected.transpose();
  }
  // Z moves the spindle (tool side): its error motion is the expansion itself, and the tool goes as far.
  const int z = machine->axisIndex("Z");
  const auto& travel = *machine->axes[static_cast<size_t>(z)].travel;
  ScaleState zScale;
  zScale.axis = z;
  zScale.sensors.positions = {travel.min, travel.max};
  zScale.sensors.referencePosition = travel.max;
  zScale.temperatures = {24.0, 21.0};
  const auto warmZ = compile(machine, atThermalState(*machine, cold, {{zScale}, std::nullopt}));
  const std::vector<double> q{100.0, 40.0, travel.min};
  const Vec3 moved = toolPoint(warmZ, q.data()).position - toolPoint(coldModel, q.data()).position;
  const double delta = scaleExpansion(zScale.sensors, zScale.temperatures, travel.min);
  EXPECT_LT((moved - delta * machine->axes[static_cast<size_t>(z)].direction).norm(), 1e-12);
  EXPECT_GT(std::fabs(delta), 1e-3);
  EXPECT_TRUE(test::thrown<InvalidInput>([&] { atThermalState(*machine, cold, {{scale, scale}, std::nullopt}); }));
}

// The compensation table written cold and written warm differ by the expansion the model
// predicts, to its second order (the expansion's own slope alpha (T - T_ref) times itself, below
// 2 nm here); each applied at its own state leaves what the grid leaves cold, the cold table on
// the warm machine leaves the expansion.
TEST(ThermalState, TablesWrittenAtTwoThermalStatesDifferByThePrediction) {
  const auto setup = loadMachineSetup({"three-axis-vertical", "", "", std::nullopt, ""});
  const auto scale = warmX(*setup.machine, {21.5, 26.0, 22.0});
  const auto warmErrors = atThermalState(*setup.machine, setup.errors, {{scale}, std::nullopt});
  const CorrectionGridSpec spec{{11, 5, 5}, {}};
  const auto coldGrid = correctionGrid(setup.machine, setup.errors, spec), warmGrid = correctionGrid(setup.machine, warmErrors, spec);
  double largest = 0.0;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 11; ++i) {
        const double delta = scaleExpansion(scale.sensors, scale.temperatures, coldGrid.node(0, i));
        const Vec3 change = warmGrid.at(i, j, k) - coldGrid.at(i, j, k);
        EXPECT_NEAR(change.x(), -delta, 2e-6) << i << " " << j << " " << k;
        EXPECT_LT(change.tail<2>().norm(), 2e-6);
        largest = std::max(largest, std::fabs(delta));
      }
  const auto applied = [](const CorrectionGrid& g) { return [&g](const Vec3& p) { return g.interpolate(p); }; };
  const auto coldOnCold = tableResidual(setup.machine, setup.errors, coldGrid, applied(coldGrid));
  const auto warmOnWarm = tableResidual(setup.machine, warmErrors, warmGrid, applied(warmGrid));
  const auto coldOnWarm = tableResidual(setup.machine, warmErrors, coldGrid, applied(coldGrid));
  EXPECT_GT(coldOnWarm.afterMax, 0.8 * largest);
  EXPECT_LT(warmOnWarm.afterMax, coldOnCold.afterMax + 1e-3);
  RecordProperty("residual_um_cold_on_cold_warm_on_warm_cold_on_warm",
                 fmt::format("{:.3f} / {:.3f} / {:.3f} (largest expansion {:.3f})", coldOnCold.afterMax * 1e3, warmOnWarm.afterMax * 1e3,
                             coldOnWarm.afterMax * 1e3, largest * 1e3));
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

TEST(ThermalStateFile, ReadsTheScalesAndNamesItsErrors) {
  const auto machine = test::bundled("three-axis-vertical");
  const auto scales = parseThermalState(*machine,
                                        "scales:\n"
                                        "  X: {sensors: [0 mm, 337 mm, 600 mm], temperatures: [21.5, 26.0, 22.0], reference: 100 mm}\n"
                                        "  Z: {sensors: [0 mm, 0.5 m], temperatures: [22, 21], reference: 500 mm, expansion: 8e-6, reference_temperature: 20.5}\n",
                                        "t.yaml")
                          .scales;
  ASSERT_EQ(scales.size(), 2u);
  EXPECT_EQ(scales[0].axis, machine->axisIndex("X"));
  EXPECT_EQ(scales[0].sensors.positions, (std::vector<double>{0, 337, 600}));
  EXPECT_EQ(scales[0].sensors.expansion, 11.5e-6);
  EXPECT_EQ(scales[1].sensors.positions, (std::vector<double>{0, 500}));
  EXPECT_EQ(scales[1].sensors.referenceTemperature, 20.5);
  const auto message = [&](const std::string& text) {
    const auto e = test::thrown<InputError>([&] { parseThermalState(*machine, text, "t.yaml"); });
    return e ? std::to_string(e->where().line) + " " + e->where().key + ": " + e->reason() : std::string();
  };
  EXPECT_EQ(message("scales:\n  C: {sensors: [0 mm, 1 mm], temperatures: [20, 20], reference: 0 mm}\n"), "2 scales.C: not a linear axis with a travel of this machine");
  EXPECT_EQ(message("scales:\n  X: {sensors: [0 mm, 0 mm], temperatures: [20, 20], reference: 0 mm}\n"), "2 scales.X.sensors: positions must increase");
  EXPECT_EQ(message("scales:\n  X: {sensors: [0 mm, 600 mm], temperatures: [20], reference: 0 mm}\n"),
            "2 scales.X.temperatures: expected 2 temperatures in degC, one per sensor");
  EXPECT_EQ(message("scales:\n  X: {sensors: [0 mm, 600 mm], temperatures: [20, .nan], reference: 0 mm}\n"), "2 scales.X.temperatures: expected a plain number, got '.nan'");
  EXPECT_EQ(message("scales:\n  X: {sensors: [0 mm, 600 mm], temperatures: [20, 20]}\n"),
            "2 scales.X.reference: missing (the position where the scale reads true, e.g. where the drift was measured)");
  EXPECT_EQ(message("scale:\n  X: {}\n"), "1 scale: unknown key (expected one of: description, scales, spindle)");
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

// The periodic update (seed 003 §2.7) as a controller's logger drives it: the state rewritten
// between two updates, the second tables written for the new temperatures and the grid said to
// move by the change of the spindle's predicted drift at the TCP.
TEST(ThermalState, KeptCurrentTheTablesFollowTheStateAsItIsRewritten) {
  const auto folder = std::filesystem::temp_directory_path() / "mtacc-tables-kept-current";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const auto state = folder / "state.yaml";
  const std::string model = test::testDataDir() + "/../../data/thermal/maho-spindle-drift-model.yaml";
  const auto writeState = [&](double head) {
    writeFileAtomically(state.string(), fmt::format("spindle: {{model: {}, temperatures: {{head: {}, column: 22, bed: 21}}, probe_above_tcp: 100 mm}}\n", model, head));
  };
  writeState(25.0);
  const MachineSource source{"three-axis-vertical", "", "", std::nullopt, state.string()};
  const auto machine = loadMachineSetup(source).machine;
  const auto atTcp = [&]() { return spindleDriftAtTcp(*machine, *loadThermalState(*machine, state.string()).spindle); };
  const Vec3 before = atTcp();
  std::vector<std::optional<double>> moves;
  PeriodicTablesRequest request;
  request.tables.grid = {{5, 4, 4}, {}};
  request.folder = (folder / "tables").string();
  request.periodSeconds = 0.01;
  request.updates = 2;
  keepTablesCurrent(source, request, [] { return false; }, [&](int update, const CompensationTablesResult& r, std::optional<double> moved) {
    moves.push_back(moved);
    EXPECT_EQ(update, static_cast<int>(moves.size()));
    EXPECT_FALSE(r.files.empty());
    EXPECT_TRUE(std::filesystem::exists(folder / "tables" / r.files.front().first));
    if (update == 1) writeState(33.0);
  });
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_FALSE(moves[0]);
  const Vec3 after = atTcp();
  ASSERT_TRUE(moves[1]);
  // As in TablesWrittenAtTwoSpindleTemperaturesDifferByThePrediction: to the machine's angular errors times the drift, below 1 nm.
  EXPECT_NEAR(*moves[1], (after - before).norm(), 1e-6);
  EXPECT_GT(*moves[1], 5e-3) << "8 K on the head moves the tool by micrometres";
  EXPECT_TRUE(test::thrown<InputError>([&] { keepTablesCurrent({"three-axis-vertical", "", "", std::nullopt, ""}, request, [] { return false; }, [](int, const auto&, auto) {}); }));
  int calls = 0;
  request.periodSeconds = 3600.0;
  request.updates = 0;
  keepTablesCurrent(source, request, [&] { return calls > 0; },
                    [&](int, const CompensationTablesResult&, std::optional<double>) { ++calls; });
  EXPECT_EQ(calls, 1) << "a stop asked while waiting ends the wait";
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace mtacc
