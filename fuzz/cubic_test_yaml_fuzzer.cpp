// A cubic machining test (YAML): block, zones, tool, pick, depth, feed.
#include "fuzz_input.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { parseCubicTest(fuzz::text(data, size), "fuzz.yaml"); });
}
