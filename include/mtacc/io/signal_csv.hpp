#pragma once
// Recorded signals (CSV, docs/file-formats.md "Recorded signals"): a header row `time_s` and
// the channel names, then one row per sample at a constant rate. Used for the NC's command
// and encoder traces (one column per axis, mm and deg) and the instrument's readings.
#include <string>
#include <vector>

#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

struct SignalLayout {
  std::vector<std::string> channels;  // required, in this order in the returned trace; no others allowed
  double expectedPeriod = 0.0;        // s; 0: any constant rate. Otherwise the file's period must agree within 0.1 %
  size_t minimumSamples = 4;
};

struct RecordedSignal {
  SampledTrace trace;  // channels in the layout's order
  int headerLine = 1;  // where a message about the whole file points
};

// Throws InputError naming file, line and column for a missing or unknown column, a value that
// is not finite, time that does not increase, a step more than 1 % off the file's typical (median) step
// (a gap, a repeated row or a rate change), a period off the expected one, or too few samples.
RecordedSignal readSignalCsv(const std::string& path, const SignalLayout& layout);
RecordedSignal parseSignalCsv(const std::string& text, const std::string& sourceName, const SignalLayout& layout);

// The file's text: `time_s` (to the nanosecond) and each channel times its scale (e.g. 1 / kDeg
// for a rotary axis, 1000 for readings in um) to ten significant digits.
std::string signalCsv(const SampledTrace& trace, const std::vector<std::string>& names, const std::vector<double>& scales);

}  // namespace mtacc
