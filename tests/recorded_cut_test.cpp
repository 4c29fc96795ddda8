// Seed 001 §4.1, Eqs 13-14: the machined surface from the axis positions a servo tool records
// during the cut instead of the programmed ones. The commanded positions as a trace give the
// programmed surface exactly; a servo offset of Z in zone I alone moves zone I and, referenced
// to it, every other zone by that offset; the CL data are the tool tips through the machine.
#include <gtest/gtest.h>

#include <fstream>

#include "mtacc/core/units.hpp"
#include "mtacc/io/recorded_signal.hpp"
#include "mtacc/workflows/cubic_test.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// The zones' commanded positions one after another, a sample every millisecond, with `offset`
// added to the Z positions of the zone `offsetZone`.
std::string traceOf(const Machine& machine, const std::vector<CubicZonePath>& path, size_t offsetZone, double offset) {
  SampledTrace trace;
  trace.period = 1e-3;
  trace.channels.resize(static_cast<size_t>(machine.commandedCount()));
  std::vector<std::string> names;
  std::vector<double> scales;
  for (int a = 0; a < machine.commandedCount(); ++a) {
    names.push_back(machine.axes[static_cast<size_t>(a)].name);
    scales.push_back(machine.axes[static_cast<size_t>(a)].isRotary() ? 1 / kDeg : 1.0);
  }
  const int z = machine.axisIndex("Z");
  for (size_t k = 0; k < path.size(); ++k)
    for (Eigen::Index i = 0; i < path[k].q.rows(); ++i)
      for (int a = 0; a < machine.commandedCount(); ++a)
        trace.channels[static_cast<size_t>(a)].push_back(path[k].q(i, a) + (k == offsetZone && a == z ? offset : 0.0));
  return signalFile(SignalFormat::Csv, trace, names, scales);
}

CubicTestStudy studyWithTrace(const MachineSetup& setup, const std::string& file) {
  CubicTestRequest request;
  request.gridSpacing = 0.1;
  request.traceFile = file;
  return cubicTestStudy(setup, request);
}

TEST(RecordedCut, CommandedPositionsGiveTheProgrammedSurface) {
  const test::TestFolder folder("mtacc-recorded-cut");
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const auto path = cubicToolPath(setup.nominal(), seed001CubicTest());
  const std::string file = (folder.dir() / "trace.csv").string();
  std::ofstream(file) << traceOf(*setup.machine, path, 0, 0.0);
  const auto s = studyWithTrace(setup, file);
  ASSERT_TRUE(s.trace);
  EXPECT_EQ(s.trace->runs.size(), path.size());  // the rotary axes change between the zones only
  EXPECT_EQ(s.trace->cuttingSamples, s.trace->samples);
  // The trace holds the positions to ten significant digits (1e-8 mm at 100 mm).
  for (size_t k = 0; k < s.zones.size(); ++k) EXPECT_NEAR(s.trace->zones[k].mean, s.zones[k].measured.mean, 1e-7) << s.zones[k].name;
  EXPECT_LT(std::abs(s.trace->map.at(100, 100) - s.actual.at(100, 100)), 1e-7);
  const auto first = toolPoint(setup.actual(), path[0].q.row(0).data(), path[0].direction.row(0).data());
  EXPECT_LT((s.trace->cl[0][0].position - first.position).norm(), 1e-7);
}

TEST(RecordedCut, AServoOffsetInTheReferenceZoneMovesEveryOtherZone) {
  // Z recorded 2 um above its command throughout zone I (B = C = 0: Z is the face normal): zone I
  // is cut 2 um higher, and every zone referenced to it 2 um lower than programmed.
  const test::TestFolder folder("mtacc-recorded-cut");
  const auto setup = loadMachineSetup({"tilting-table", "", "", std::nullopt, ""});
  const auto spec = seed001CubicTest();
  const auto path = cubicToolPath(setup.nominal(), spec);
  const size_t reference = referenceZone(spec);
  const std::string file = (folder.dir() / "trace.csv").string();
  std::ofstream(file) << traceOf(*setup.machine, path, reference, 0.002);
  const auto s = studyWithTrace(setup, file);
  ASSERT_TRUE(s.trace);
  for (size_t k = 0; k < s.zones.size(); ++k) {
    if (k == reference) continue;
    EXPECT_NEAR(s.trace->zones[k].mean - s.zones[k].measured.mean, -0.002, 1e-6) << s.zones[k].name;
  }
  const auto unreferenced = zonePlanes(s.trace->map, spec, 1.0), programmed = zonePlanes(s.actual, spec, 1.0);
  EXPECT_NEAR(unreferenced[reference].mean - programmed[reference].mean, 0.002, 1e-6);
}

}  // namespace
}  // namespace mtacc
