// Seed 003's classification (BCR report 1991, Tables 2.2 and 2.3, L345-452) of the bundled
// machines, each worked out by hand from the table: the linear axes of the tool chain (A) and
// the workpiece chain (B) from the bed, horizontal or vertical, and the sides of the rotary axes.
// The Maho machine is class IA with rotary class 2 (the extraction's reading of ch. 3 and App.
// A: a horizontal ram on the tool side, a knee-type Y-X table carrying B; the report does not
// state its class).
#include <gtest/gtest.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/machine/machine_class.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(MachineClass, BundledMachinesByTables2_2And2_3) {
  struct Expected {
    const char* machine;
    const char* chains;
    const char* linear;
    int rotary;
    size_t notes;  // why a class is missing
  };
  const Expected expected[] = {{"maho", "A: H, B: V->H", "IA", 2, 0},
                               {"three-axis-vertical", "A: V, B: H->H", "IB", 0, 0},  // no rotary axis: nothing to say
                               {"tilting-table", "A: H->V, B: H", "IIB", 1, 0},
                               {"swivel-head-table", "A: H->V, B: H", "IIB", 2, 0},
                               {"double-pivot-head", "A: H->V, B: H", "IIB", 3, 0},
                               {"inclined-a-table", "A: H->V, B: H", "IIB", 0, 1},  // A and C are not perpendicular
                               {"multitasking-b-c", "A: V->H->H, B: -", "", 2, 1}};  // a lathe: no row of Table 2.2
  for (const auto& e : expected) {
    SCOPED_TRACE(e.machine);
    const auto c = classifyMachine(*test::bundled(e.machine));
    EXPECT_EQ(c.chains, e.chains);
    EXPECT_EQ(c.linear, e.linear);
    EXPECT_EQ(c.rotary, e.rotary);
    EXPECT_EQ(c.notes.size(), e.notes);
  }
  EXPECT_EQ(classifyMachine(*test::bundled("maho")).typeDependentErrors,
            (std::vector<std::string>{"table guide = F(table, weight/load)", "ram = F(ram)"}));
}

// The travelling-bridge and travelling-column rows, and an inclined linear axis.
TEST(MachineClass, ThreeAxesOnTheToolSideAndAnInclinedAxis) {
  const std::string head = "name: m\naxes:\n  X: {direction: [1, 0, 0], travel: [0 mm, 1 mm]}\n  Y: {direction: [0, 1, 0], travel: [0 mm, 1 mm]}\n";
  const auto bridge = parseMachine("structure: t-Z-Y-X-b-w\n" + head + "  Z: {direction: [0, 0, 1], travel: [0 mm, 1 mm]}\n", "m.yaml");
  EXPECT_EQ(classifyMachine(bridge).linear, "IIIA");
  const auto column = parseMachine("structure: t-Z-Y-X-b-w\nvertical: [0, 1, 0]\n" + head + "  Z: {direction: [0, 0, 1], travel: [0 mm, 1 mm]}\n", "m.yaml");
  EXPECT_EQ(classifyMachine(column).linear, "IIIB");
  const auto inclined = parseMachine("structure: t-Z-Y-X-b-w\n" + head + "  Z: {direction: [0, 1, 1], travel: [0 mm, 1 mm]}\n", "m.yaml");
  const auto c = classifyMachine(inclined);
  EXPECT_EQ(c.linear, "");
  ASSERT_EQ(c.notes.size(), 1u);
  EXPECT_EQ(c.notes[0], "Z is neither horizontal nor vertical");
  EXPECT_THROW(parseMachine("structure: t-Z-Y-X-b-w\nvertical: [0, 0, 0]\n" + head + "  Z: {direction: [0, 0, 1]}\n", "m.yaml"), InputError);
}

}  // namespace
}  // namespace mtacc
