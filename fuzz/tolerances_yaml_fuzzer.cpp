// Tolerance files, each tolerance evaluated at a few measured lengths and judged.
#include "fuzz_input.hpp"
#include "mtacc/io/tolerances_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const auto set = parseTolerances(fuzz::text(data, size), "fuzz.yaml");
    for (const auto& entry : set.entries)
      for (const double length : {0.0, 40.0, 1000.0, 5000.0}) decide(1e-3, 5e-4, entry.tolerance.at(length), set.rule);
  });
}
