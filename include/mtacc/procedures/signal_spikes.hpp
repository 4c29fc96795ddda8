#pragma once
// Single samples that stand out from a sampled signal (a spike of the instrument, a lost
// sample): robust statistics, so that the spikes themselves do not set the scale they are
// judged against.
#include <vector>

#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

// The samples (indices, ascending) at which some channel departs from the median of the
// kWindow samples around it by more than `threshold` times the robust standard deviation of
// those departures (1.4826 times their median absolute value) over the whole channel, and by
// more than `floor` (the channel's unit) so that a noise-free signal's rounding is not flagged.
constexpr size_t kSpikeWindow = 7;
std::vector<size_t> spikeSamples(const SampledTrace& trace, double threshold = 8.0, double floor = 1e-5);

}  // namespace mtacc
