// A test plan for the tilting table.
#include "fuzz_input.hpp"
#include "mtacc/io/plan_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto nominal = compileNominal(fuzz::bundled("tilting-table"));
  return fuzz::asTheFrontEndsDo([&] { parseTestPlan(nominal, fuzz::text(data, size), "fuzz.yaml"); });
}
