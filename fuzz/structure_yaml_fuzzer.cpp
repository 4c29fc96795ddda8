// A rigid-body structure model, assembled at its home position.
#include "fuzz_input.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "mtacc/io/structure_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { assembleStructure(parseStructure(fuzz::text(data, size), "fuzz.yaml"), {}); });
}
