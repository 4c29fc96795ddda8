// Hole- and ball-plate measurements (CSV) for the Maho machine, read and processed (temperatures,
// misalignment).
#include "fuzz_input.hpp"
#include "mtacc/io/artefact_csv.hpp"
#include "mtacc/workflows/artefacts.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("maho");
  return fuzz::asTheFrontEndsDo([&] {
    const auto m = parsePlateMeasurement(*machine, fuzz::text(data, size), "fuzz.csv");
    const auto a = artefactFromPlate(m);
    const auto c = artefactCoordinates(a);
    alignArtefact(c.calibrated, c.measured, a.placement.probed, a.artefact.dimension, a.alignment);
  });
}
