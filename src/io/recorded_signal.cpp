#include "mtacc/io/recorded_signal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/io/npy.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

constexpr size_t kHeader = static_cast<size_t>(-1);

// The columns of either format and where sample k of a column is (kHeader: the file as a whole).
struct SignalColumns {
  std::string source;
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::function<InputLocation(size_t sample, const std::string& column)> locate;
};

// The chosen channels are moved out of `file`.
RecordedSignal checkedSignal(SignalColumns file, const SignalLayout& layout, int headerLine) {
  std::vector<std::string> names{"time_s"};
  names.insert(names.end(), layout.channels.begin(), layout.channels.end());
  std::vector<size_t> columns;
  for (const auto& name : names) {
    const auto found = std::find(file.names.begin(), file.names.end(), name);
    if (found == file.names.end()) throw InputError(file.locate(kHeader, name), "missing column '" + name + "'");
    columns.push_back(static_cast<size_t>(found - file.names.begin()));
  }
  for (const auto& name : file.names)
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError(file.locate(kHeader, name), fmt::format("unknown column; expected time_s, {}", fmt::join(layout.channels, ", ")));

  const auto& time = file.values[columns[0]];
  const size_t n = time.size(), needed = std::max<size_t>(layout.minimumSamples, 4);
  if (n < needed) throw InputError(file.locate(n == 0 ? kHeader : n - 1, "time_s"), fmt::format("{} samples, at least {} needed", n, needed));
  for (const size_t c : columns)
    for (size_t k = 0; k < n; ++k)
      if (!std::isfinite(file.values[c][k])) throw InputError(file.locate(k, file.names[c]), "not a finite number");
  for (size_t k = 1; k < n; ++k)
    if (!(time[k] > time[k - 1]))
      throw InputError(file.locate(k, "time_s"), fmt::format("time does not increase ({} s after {} s)", time[k], time[k - 1]));
  std::vector<double> steps(n - 1);
  for (size_t k = 1; k < n; ++k) steps[k - 1] = time[k] - time[k - 1];
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  const double typical = steps[steps.size() / 2];
  for (size_t k = 1; k < n; ++k) {
    const double step = time[k] - time[k - 1];
    if (std::fabs(step - typical) > 0.01 * typical)
      throw InputError(file.locate(k, "time_s"),
                       fmt::format("a step of {:.6g} ms where the file's period is {:.6g} ms: a gap or a change of rate", step * 1e3, typical * 1e3));
  }
  const double period = (time[n - 1] - time[0]) / static_cast<double>(n - 1);
  if (layout.expectedPeriod > 0 && std::fabs(period - layout.expectedPeriod) > 1e-3 * layout.expectedPeriod)
    throw InputError(file.locate(n - 1, "time_s"),
                     fmt::format("recorded at {:.6g} Hz where {:.6g} Hz is expected", 1.0 / period, 1.0 / layout.expectedPeriod));

  RecordedSignal signal{{time[0], period, {}}, headerLine};
  for (size_t c = 1; c < columns.size(); ++c) signal.trace.channels.push_back(std::move(file.values[columns[c]]));
  return signal;
}

}  // namespace

RecordedSignal parseSignalCsv(const std::string& text, const std::string& source, const SignalLayout& layout) {
  const auto table = parseCsv(text, source);
  SignalColumns file{source, table.header, std::vector<std::vector<double>>(table.header.size(), std::vector<double>(table.rows.size())),
                     [&](size_t sample, const std::string& column) {
                       return InputLocation{source, sample == kHeader ? table.headerLine : table.lines[sample], column};
                     }};
  for (size_t k = 0; k < table.rows.size(); ++k)
    for (size_t c = 0; c < table.header.size(); ++c) file.values[c][k] = table.rows[k][c];
  return checkedSignal(std::move(file), layout, table.headerLine);
}

RecordedSignal parseSignalNpy(const std::string& bytes, const std::string& source, const SignalLayout& layout) {
  auto records = parseNpyRecords(bytes, source);
  SignalColumns file{source, std::move(records.names), std::move(records.columns), [&](size_t sample, const std::string& column) {
                       return InputLocation{source, 0, sample == kHeader ? column : fmt::format("{}[{}]", column, sample)};
                     }};
  return checkedSignal(std::move(file), layout, 0);
}

RecordedSignal readRecordedSignal(const std::string& path, const SignalLayout& layout) {
  const bool npy = path.size() >= 4 && path.compare(path.size() - 4, 4, ".npy") == 0;
  return npy ? parseSignalNpy(readTextFile(path), path, layout) : parseSignalCsv(readTextFile(path), path, layout);
}

std::string signalFile(SignalFormat format, const SampledTrace& trace, const std::vector<std::string>& names, const std::vector<double>& scales) {
  if (format == SignalFormat::Npy) {
    NpyRecords records{{"time_s"}, {std::vector<double>(trace.samples())}};
    for (size_t k = 0; k < trace.samples(); ++k) records.columns[0][k] = trace.start + trace.period * static_cast<double>(k);
    for (size_t c = 0; c < trace.channels.size(); ++c) {
      records.names.push_back(names[c]);
      auto& column = records.columns.emplace_back(trace.channels[c]);
      for (double& v : column) v *= scales[c];
    }
    return npyRecords(records);
  }
  std::string out = fmt::format("time_s,{}\n", fmt::join(names, ","));
  for (size_t k = 0; k < trace.samples(); ++k) {
    out += fmt::format("{:.9f}", trace.start + trace.period * static_cast<double>(k));
    for (size_t c = 0; c < trace.channels.size(); ++c) out += fmt::format(",{:.10g}", trace.channels[c][k] * scales[c]);
    out += '\n';
  }
  return out;
}

const char* extensionOf(SignalFormat format) { return format == SignalFormat::Npy ? "npy" : "csv"; }

SignalFormat signalFormatNamed(const std::string& name, const std::string& key) {
  for (const auto format : {SignalFormat::Csv, SignalFormat::Npy})
    if (name == extensionOf(format)) return format;
  throw InputError({"", 0, key}, fmt::format("'{}': expected csv or npy", name));
}

}  // namespace mtacc
