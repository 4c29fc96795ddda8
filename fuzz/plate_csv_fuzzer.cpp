// Hole- and ball-plate measurements (CSV) for the Maho machine, read and processed (temperatures,
// misalignment).
#include "fuzz_input.hpp"
#include "mtacc/io/plate_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("maho");
  return fuzz::asTheFrontEndsDo([&] {
    const auto m = parsePlateMeasurement(*machine, fuzz::text(data, size), "fuzz.csv");
    plateDeviations(m.plate, m.features, m.measured, m.temperatures);
  });
}
