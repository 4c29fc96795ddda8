// Seed 002's six ball-bar eccentricities and set-up (YAML), read and identified.
#include "fuzz_input.hpp"
#include "mtacc/io/seed002_eccentricities_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const auto m = parseSeed002Eccentricities(fuzz::text(data, size), "fuzz.yaml");
    identifySeed002(m.eccentricities, m.setup);
  });
}
