// A pose or target CSV for the tilting table (axis columns, plus tool-direction columns).
#include "fuzz_input.hpp"
#include "mtacc/io/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("tilting-table");
  return fuzz::asTheFrontEndsDo([&] { posesFromCsv(*machine, parseCsv(fuzz::text(data, size), "fuzz.csv"), {"i", "j", "k"}); });
}
