// ISO 230-2 positioning tests (KEY=value or CSV), read and evaluated.
#include "fuzz_input.hpp"
#include "mtacc/io/positioning_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { evaluatePositioning(parsePositioningTest(fuzz::text(data, size), "fuzz.dat")); });
}
