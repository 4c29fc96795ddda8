// Zone results of a cubic machining test (CSV: zone, height, optional tilts, '# noise:').
#include "fuzz_input.hpp"
#include "mtacc/io/zone_results_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] { parseZoneResults(fuzz::text(data, size), "fuzz.csv"); });
}
