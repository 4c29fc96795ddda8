// Acceptance tests files (the tests, their files and instruments).
#include "fuzz_input.hpp"
#include "mtacc/io/acceptance_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { parseAcceptancePlan(fuzz::text(data, size), "fuzz/tests.yaml"); });
}
