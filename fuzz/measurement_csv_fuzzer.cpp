// A measurement file (any instrument) for the tilting table.
#include "fuzz_input.hpp"
#include "mtacc/io/measurement_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto nominal = compileNominal(fuzz::bundled("tilting-table"));
  return fuzz::asTheFrontEndsDo([&] { parseMeasurementCsv(nominal, fuzz::text(data, size), "fuzz.csv"); });
}
