#include "mtacc/io/signal_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/csv.hpp"
#include "mtacc/io/text_file.hpp"

namespace mtacc {

RecordedSignal parseSignalCsv(const std::string& text, const std::string& source, const SignalLayout& layout) {
  const auto table = parseCsv(text, source);
  std::vector<std::string> names{"time_s"};
  names.insert(names.end(), layout.channels.begin(), layout.channels.end());
  const auto columns = requireColumns(table, names);
  if (table.header.size() != names.size())
    for (const auto& name : table.header)
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw InputError({source, table.headerLine, name},
                         fmt::format("unknown column; expected time_s, {}", fmt::join(layout.channels, ", ")));

  const size_t n = table.rows.size();
  if (n < std::max<size_t>(layout.minimumSamples, 4))
    throw InputError({source, table.lines.back(), "time_s"},
                     fmt::format("{} samples, at least {} needed", n, std::max<size_t>(layout.minimumSamples, 4)));
  const auto time = [&](size_t k) { return table.rows[k][columns[0]]; };
  for (size_t k = 1; k < n; ++k)
    if (!(time(k) > time(k - 1)))
      throw InputError({source, table.lines[k], "time_s"}, fmt::format("time does not increase ({} s after {} s)", time(k), time(k - 1)));
  std::vector<double> steps(n - 1);
  for (size_t k = 1; k < n; ++k) steps[k - 1] = time(k) - time(k - 1);
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  const double typical = steps[steps.size() / 2];
  for (size_t k = 1; k < n; ++k) {
    const double step = time(k) - time(k - 1);
    if (std::fabs(step - typical) > 0.01 * typical)
      throw InputError({source, table.lines[k], "time_s"},
                       fmt::format("a step of {:.6g} ms where the file's period is {:.6g} ms: a gap or a change of rate", step * 1e3, typical * 1e3));
  }
  const double period = (time(n - 1) - time(0)) / static_cast<double>(n - 1);
  if (layout.expectedPeriod > 0 && std::fabs(period - layout.expectedPeriod) > 1e-3 * layout.expectedPeriod)
    throw InputError({source, table.lines.back(), "time_s"},
                     fmt::format("recorded at {:.6g} Hz where {:.6g} Hz is expected", 1.0 / period, 1.0 / layout.expectedPeriod));

  RecordedSignal signal{{time(0), period, {}}, table.headerLine};
  for (size_t c = 1; c < columns.size(); ++c) {
    auto& channel = signal.trace.channels.emplace_back(n);
    for (size_t k = 0; k < n; ++k) channel[k] = table.rows[k][columns[c]];
  }
  return signal;
}

RecordedSignal readSignalCsv(const std::string& path, const SignalLayout& layout) {
  return parseSignalCsv(readTextFile(path), path, layout);
}

std::string signalCsv(const SampledTrace& trace, const std::vector<std::string>& names, const std::vector<double>& scales) {
  std::string out = fmt::format("time_s,{}\n", fmt::join(names, ","));
  for (size_t k = 0; k < trace.samples(); ++k) {
    out += fmt::format("{:.9f}", trace.start + trace.period * static_cast<double>(k));
    for (size_t c = 0; c < trace.channels.size(); ++c) out += fmt::format(",{:.10g}", trace.channels[c][k] * scales[c]);
    out += '\n';
  }
  return out;
}

}  // namespace mtacc
