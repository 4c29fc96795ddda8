// Scanned surfaces (CSV, PLY, STL) read and fitted onto the cubic test's cells as `cubic --scan`
// does; the first byte picks the form, the rest is the file.
#include "fuzz_input.hpp"
#include "mtacc/io/point_cloud.hpp"
#include "mtacc/workflows/cubic_test.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  if (size == 0) return 0;
  static const char* const forms[] = {"csv", "ply", "stl"};
  static const auto spec = seed001CubicTest();
  return fuzz::asTheFrontEndsDo([&] {
    const auto points = parsePointCloud(fuzz::text(data + 1, size - 1), forms[data[0] % 3], "fuzz");
    scannedCubicTest(points, spec, 1.0, 1.0, referenceZone(spec), "fuzz");
  });
}
