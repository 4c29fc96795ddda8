// Points probed on a cone-frustum test piece (CSV), read and evaluated as `cone --measured` does:
// sections, least-squares and minimum-zone circles, the best-fit cone.
#include "fuzz_input.hpp"
#include "mtacc/io/cone_points_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { evaluateMeasuredCone(parseConePoints(fuzz::text(data, size), "fuzz.csv"), 0.785); });
}
