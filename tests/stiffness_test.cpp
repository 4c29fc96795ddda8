// Finite stiffness (seed 003 §4.2, §5.4): changes of component errors with another axis's
// position and the workpiece load, read from YAML and evaluated in the kinematics.
#include <gtest/gtest.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/stiffness.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

const std::string kLoadFile = bundledDataDir() + "/stiffness/maho-260kg.yaml";

StiffnessError twoAxisTerm() {
  StiffnessError s;
  s.axis = 2;
  s.component = 3;
  s.otherAxis = 3;
  s.positions = {0.0, 100.0, 300.0};
  s.otherPositions = {0.0, 350.0, 700.0};
  s.values.resize(3, 3);
  s.values << 1, 2, 3,  //
      4, 6, 8,          //
      0, -2, 5;
  s.referenceLoad = 260.0;
  return s;
}

TEST(StiffnessError, ExactAtTheMeasuredPositionsLinearBetweenHeldBeyond) {
  const auto s = twoAxisTerm();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(s.value(s.positions[i], s.otherPositions[k]), s.values(i, k));
  // Halfway in both: the mean of the four corners; a quarter of the way along the own axis alone.
  EXPECT_DOUBLE_EQ(s.value(50.0, 175.0), (1 + 2 + 4 + 6) / 4.0);
  EXPECT_DOUBLE_EQ(s.value(200.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(s.value(25.0, 350.0), 2.0 + 0.25 * (6.0 - 2.0));
  EXPECT_DOUBLE_EQ(s.value(-50.0, -10.0), 1.0);
  EXPECT_DOUBLE_EQ(s.value(900.0, 900.0), 5.0);
}

TEST(StiffnessError, LinearInTheLoadOrIndependentOfIt) {
  auto s = twoAxisTerm();
  EXPECT_DOUBLE_EQ(s.loadFactor(0.0), 0.0);
  EXPECT_DOUBLE_EQ(s.loadFactor(130.0), 0.5);
  EXPECT_DOUBLE_EQ(s.loadFactor(520.0), 2.0);
  s.referenceLoad = 0.0;
  EXPECT_DOUBLE_EQ(s.loadFactor(520.0), 1.0);
}

// At a measured position of the other axis the change is a table of its own axis: the machine
// with it equals the machine with that column as a linear table term, pose by pose.
TEST(Stiffness, AtAMeasuredPositionOfTheOtherAxisItActsAsATableOfItsOwnAxis) {
  const auto machine = test::bundled("maho");
  const auto withChange = parseErrors(*machine, R"(workpiece_load: 130 kg
errors:
  yrx:
    stiffness: {load: 260 kg, with: X, unit: arcsec, positions: [0 mm, 250 mm, 500 mm], with_positions: [0 mm, 350 mm, 700 mm],
                values: [[3, 1.5, 3.2], [1.5, 0.6, 1.6], [0.4, 0.1, 0.5]]}
)", "change");
  const auto asTable = parseErrors(*machine, R"(errors:
  yrx: {table: {interpolation: linear, positions: [0 mm, 250 mm, 500 mm], values: [0.75 arcsec, 0.3 arcsec, 0.05 arcsec]}}
)", "table");
  ASSERT_EQ(withChange.stiffness.size(), 1u);
  const auto a = compile(machine, withChange), b = compile(machine, asTable);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    auto q = test::randomPose(*machine, rng);
    q[static_cast<size_t>(machine->axisIndex("X"))] = 350.0;
    const Pose pa = toolInWorkpiece(a, q.data()), pb = toolInWorkpiece(b, q.data());
    EXPECT_LT((pa.translation() - pb.translation()).norm(), 1e-12) << machine->describePose(q);
    EXPECT_LT((pa.linear() - pb.linear()).norm(), 1e-15);
  }
}

// The bundled 260 kg file adds to App. D: without the load the machine is App. D's; the TCP
// change grows with the load, linearly to first order (the rotations compose exactly, so the
// second-order remainder, about (30 urad)^2 x 1 m = 1 nm, is the tolerance).
TEST(Stiffness, BundledLoadFileAddsToTheMachinesErrorsAndScalesWithTheLoad) {
  const auto machine = test::bundled("maho");
  const ErrorModel loaded = loadErrors(*machine, kLoadFile);
  EXPECT_EQ(loaded.workpieceLoad, 260.0);
  EXPECT_EQ(loaded.stiffness.size(), 5u);
  const ErrorModel geometric = loadMachineErrors(*machine);
  EXPECT_EQ(parameterCatalogue(*machine, loaded).size(), parameterCatalogue(*machine, geometric).size());
  auto atLoad = [&](double kg) {
    ErrorModel e = loaded;
    e.workpieceLoad = kg;
    return compile(machine, e);
  };
  const auto appendixD = compile(machine, geometric), empty = atLoad(0.0), half = atLoad(130.0), full = atLoad(260.0);
  std::mt19937 rng(5);
  double largest = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = test::randomPose(*machine, rng);
    const Vec3 base = toolInWorkpiece(appendixD, q.data()).translation();
    EXPECT_EQ((toolInWorkpiece(empty, q.data()).translation() - base).norm(), 0.0);
    const Vec3 dHalf = toolInWorkpiece(half, q.data()).translation() - base;
    const Vec3 dFull = toolInWorkpiece(full, q.data()).translation() - base;
    EXPECT_LT((dFull - 2.0 * dHalf).norm(), 1e-6) << machine->describePose(q);
    largest = std::max(largest, dFull.norm());
  }
  EXPECT_GT(largest, 5e-3);  // the changes reach several um, so the comparison above means something
}

TEST(Stiffness, OneErrorAloneCarriesNoStiffnessChange) {
  const auto machine = test::bundled("maho");
  const ErrorModel loaded = loadErrors(*machine, kLoadFile);
  const auto p = findParameter(*machine, loaded, "X0B");
  EXPECT_TRUE(singleError(*machine, loaded, p, 1e-3).stiffness.empty());
}

// The summary's three largest errors from their definitions: geometric (no changes), the
// changes alone (no geometric errors), and what the changes add.
TEST(Stiffness, SummaryComparesTheChangesWithTheGeometricErrors) {
  MachineSource source{"maho", kLoadFile, "", std::nullopt, ""};
  const auto loaded = summariseStiffness(loadMachineSetup(source), 3);
  source.load = 0.0;
  const auto unloaded = summariseStiffness(loadMachineSetup(source), 3);
  EXPECT_EQ(loaded.poses, 243);
  EXPECT_DOUBLE_EQ(loaded.geometric.value, unloaded.geometric.value);
  EXPECT_EQ(unloaded.stiffness.value, 0.0);
  EXPECT_EQ(unloaded.change.value, 0.0);
  EXPECT_GT(loaded.stiffness.value, 5e-3);
  EXPECT_GT(loaded.change.value, 0.5 * loaded.stiffness.value);
  source.errorsFile.clear();
  EXPECT_THROW(summariseStiffness(loadMachineSetup(source), 3), InputError);
}

void expectError(const std::string& yaml, const std::string& key, const std::string& words) {
  const auto machine = test::bundled("maho");
  const auto e = test::thrown<InputError>([&] { parseErrors(*machine, yaml, "f.yaml"); });
  ASSERT_TRUE(e);
  EXPECT_EQ(e->where().key, key) << e->what();
  EXPECT_NE(std::string(e->what()).find(words), std::string::npos) << e->what();
}

TEST(Stiffness, BadInputIsLocated) {
  const std::string change = "\nerrors:\n  yrx:\n    stiffness: {load: 260 kg, unit: arcsec, positions: [0 mm, 500 mm], ";
  expectError("errors:\n  yrx:\n    stiffness: {load: 260 kg, unit: arcsec, positions: [0 mm, 500 mm], values: [1, 2]}\n",
              "workpiece_load", "e.g. 'workpiece_load: 260 kg'");
  expectError("workpiece_load: 260" + change + "values: [1, 2]}\n", "workpiece_load", "not a mass");
  expectError("workpiece_load: -5 kg" + change + "values: [1, 2]}\n", "workpiece_load", "not a load");
  expectError("workpiece_load: 260 kg" + change + "with: Y, with_positions: [0 mm, 1 mm], values: [[1, 2], [3, 4]]}\n",
              "errors.yrx.stiffness.with", "own position");
  expectError("workpiece_load: 260 kg" + change + "with: Q, with_positions: [0 mm, 1 mm], values: [[1, 2], [3, 4]]}\n",
              "errors.yrx.stiffness.with", "not a commanded axis");
  expectError("workpiece_load: 260 kg" + change + "with: X, with_positions: [0 mm, 1 mm], values: [[1, 2], [3]]}\n",
              "errors.yrx.stiffness.values", "a row of 2 values");
  expectError("workpiece_load: 260 kg" + change + "values: [1, 2, 3]}\n", "errors.yrx.stiffness.values", "one value per position (2)");
  expectError("workpiece_load: 260 kg" + change + "with_positions: [0 mm, 1 mm], values: [1, 2]}\n",
              "errors.yrx.stiffness.with_positions", "needs 'with'");
  expectError("errors:\n  yrx:\n    stiffness: {unit: arcsec, positions: [0 mm, 500 mm], values: [1, 2]}\n", "errors.yrx.stiffness",
              "needs 'load'");
  expectError("errors:\n  yrx:\n    stiffness: {with: X, unit: um, positions: [0 mm, 500 mm], with_positions: [0 mm, 1 mm], values: [[1, 2], [3, 4]]}\n",
              "errors.yrx.stiffness.unit", "an angle");
  expectError("errors:\n  yrx:\n    stiffness: {with: X, unit: arcsec, positions: [0 mm, 500 mm, 400 mm], with_positions: [0 mm, 1 mm], "
              "values: [[1, 2], [3, 4], [5, 6]]}\n",
              "errors.yrx.stiffness.positions", "increase strictly");
  expectError("errors:\n  yrx: {constant: 1 urad}\n  EAY: {constant: 1 urad}\n", "errors.EAY", "given twice");
}

}  // namespace
}  // namespace mtacc
