// Decomposition sets (YAML) for the seed 004 decomposition.
#include "fuzz_input.hpp"
#include "mtacc/io/decomposition_set_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { parseDecompositionSet(fuzz::text(data, size), "fuzz.yaml"); });
}
