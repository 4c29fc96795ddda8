#pragma once
// Recorded signals (docs/file-formats.md "Recorded signals"): time-stamped channels at a
// constant rate, as CSV (a header row `time_s` and the channel names, then one row per sample)
// or as NumPy .npy (a structured array with the fields `time_s` and the channel names). Used for
// the NC's command and encoder traces (one channel per axis, mm and deg) and the instrument's
// readings.
#include <string>
#include <vector>

#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

enum class SignalFormat { Csv, Npy };

struct SignalLayout {
  std::vector<std::string> channels;  // required, in this order in the returned trace; no others allowed
  double expectedPeriod = 0.0;        // s; 0: any constant rate. Otherwise the file's period must agree within 0.1 %
  size_t minimumSamples = 4;
};

struct RecordedSignal {
  SampledTrace trace;  // channels in the layout's order
  int headerLine = 1;  // where a message about the whole file points (0 for .npy)
};

// Both formats throw InputError naming the file and the column, and the line (CSV) or the
// record as `column[index]` (.npy), for a missing or unknown column, a value that is not
// finite, time that does not increase, a step more than 1 % off the file's typical (median) step
// (a gap, a repeated row or a rate change), a period off the expected one, or too few samples.
// The format follows the path's ending: `.npy`, else CSV.
RecordedSignal readRecordedSignal(const std::string& path, const SignalLayout& layout);
RecordedSignal parseSignalCsv(const std::string& text, const std::string& sourceName, const SignalLayout& layout);
RecordedSignal parseSignalNpy(const std::string& bytes, const std::string& sourceName, const SignalLayout& layout);

// The file: `time_s` and each channel times its scale (e.g. 1 / kDeg for a rotary axis, 1000 for
// readings in um); in CSV, time to the nanosecond and channels to ten significant digits.
std::string signalFile(SignalFormat format, const SampledTrace& trace, const std::vector<std::string>& names, const std::vector<double>& scales);
// "csv" or "npy".
const char* extensionOf(SignalFormat format);
// The format named "csv" or "npy"; InputError under `key` otherwise.
SignalFormat signalFormatNamed(const std::string& name, const std::string& key);

}  // namespace mtacc
