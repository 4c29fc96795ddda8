// Calibrated-artefact measurements (CSV) for the Maho machine, read and aligned the way the
// evaluation does (least squares or three-point, along the probed directions).
#include "fuzz_input.hpp"
#include "mtacc/workflows/artefacts.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("maho");
  return fuzz::asTheFrontEndsDo([&] {
    const auto m = parseArtefactMeasurement(*machine, fuzz::text(data, size), "fuzz.csv");
    if (m.measured.rows() == 0) return;
    const auto c = artefactCoordinates(m);
    alignArtefact(c.calibrated, c.measured, m.placement.probed, m.artefact.dimension, m.alignment);
  });
}
