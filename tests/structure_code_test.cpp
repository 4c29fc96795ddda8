#include <gtest/gtest.h>

#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/machine/structure_code.hpp"

namespace mtacc {
namespace {

using Chain = std::vector<std::string>;

TEST(StructureCode, ToolFirstTiltingTable) {
  const auto c = parseStructureCode("t-(C)-Z-Y-b-X-B-C-w");
  EXPECT_EQ(c.toolChain, (Chain{"Y", "Z"}));
  EXPECT_EQ(c.workpieceChain, (Chain{"X", "B", "C"}));
  EXPECT_EQ(c.spindle, "C");
  EXPECT_EQ(c.toolFirst(), "t-(C)-Z-Y-b-X-B-C-w");
}

TEST(StructureCode, ToolFirstHeads) {
  EXPECT_EQ(parseStructureCode("t-(C)-B-Z-Y-b-X-C-w").toolChain, (Chain{"Y", "Z", "B"}));
  EXPECT_EQ(parseStructureCode("t-(C)-B-C-Z-Y-b-X-w").toolChain, (Chain{"Y", "Z", "C", "B"}));
}

TEST(StructureCode, WorkpieceFirstSeed002) {
  const auto c = parseStructureCode("w-C'bZYXB(C1)-t");
  EXPECT_EQ(c.workpieceChain, (Chain{"C"}));
  EXPECT_EQ(c.toolChain, (Chain{"Z", "Y", "X", "B"}));
  EXPECT_EQ(c.spindle, "C1");
  EXPECT_EQ(c.toolFirst(), "t-(C1)-B-X-Y-Z-b-C-w");
}

TEST(StructureCode, WorkpieceFirstSeed004WithFrameLetter) {
  const auto c = parseStructureCode("WCAYFXZT");
  EXPECT_EQ(c.workpieceChain, (Chain{"Y", "A", "C"}));
  EXPECT_EQ(c.toolChain, (Chain{"X", "Z"}));
  EXPECT_FALSE(c.spindle);
}

TEST(StructureCode, Rejects) {
  EXPECT_THROW(parseStructureCode("t-Z-Q-b-X-w"), InvalidInput);   // unknown letter
  EXPECT_THROW(parseStructureCode("t-Z-Y-X-w"), InvalidInput);     // no bed
  EXPECT_THROW(parseStructureCode("t-Z-b-Z-w"), InvalidInput);     // axis twice
  EXPECT_THROW(parseStructureCode("t-Z-(C)-b-X-w"), InvalidInput); // spindle not at the tool
  EXPECT_THROW(parseStructureCode("Z-b-X-w"), InvalidInput);       // no tool end
  EXPECT_THROW(parseStructureCode("t-Z-b-X-t"), InvalidInput);     // both ends tool
}

}  // namespace
}  // namespace mtacc
