// Monte Carlo tolerance limits for the tilting table.
#include "fuzz_input.hpp"
#include "mtacc/io/limits_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("tilting-table");
  return fuzz::asTheFrontEndsDo([&] { parseErrorLimits(*machine, fuzz::text(data, size), "fuzz.yaml"); });
}
