// Recorded signals (NumPy .npy) for the seed 004 decomposition: a five-axis trace, resampled and
// aligned against itself as the pipeline does.
#include "fuzz_input.hpp"
#include "mtacc/io/recorded_signal.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const auto signal = parseSignalNpy(fuzz::text(data, size), "fuzz.npy", {{"X", "Y", "Z", "A", "C"}});
    const auto& trace = signal.trace;
    resampleTrace(trace, 0.0, EvenTimes{trace.start, (trace.end() - trace.start) / 2, 3});
    estimateClockOffset(trace, trace, {-2 * trace.period, 2 * trace.period});
  });
}
