// Direct-measurement runs of one component (CSV) for the Maho machine, read, averaged and
// searched for disturbed readings.
#include "fuzz_input.hpp"
#include "mtacc/io/component_runs_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("maho");
  return fuzz::asTheFrontEndsDo([&] {
    const auto f = parseComponentRuns(*machine, fuzz::text(data, size), "fuzz.csv");
    averageRuns(f.runs);
    findDisturbances(f.runs);
  });
}
