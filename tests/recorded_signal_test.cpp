// Recorded signals (CSV and .npy): channels in the layout's order whatever the file's, the period
// from the time column, and the located errors of a bad file.
#include <gtest/gtest.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/npy.hpp"
#include "mtacc/io/recorded_signal.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

constexpr const char* kTrace =
    "# an encoder trace\n"
    "time_s,B,A\n"
    "0.100,1,10\n"
    "0.103,2,20\n"
    "0.106,3,30\n"
    "0.109,4,40\n"
    "0.112,5,50\n";

TEST(SignalCsv, ChannelsComeInTheLayoutsOrderWithTheFilesPeriod) {
  const auto signal = parseSignalCsv(kTrace, "t.csv", {{"A", "B"}, 0.003});
  EXPECT_EQ(signal.headerLine, 2);
  EXPECT_DOUBLE_EQ(signal.trace.start, 0.1);
  EXPECT_NEAR(signal.trace.period, 0.003, 1e-15);
  ASSERT_EQ(signal.trace.channels.size(), 2u);
  EXPECT_EQ(signal.trace.channels[0], (std::vector<double>{10, 20, 30, 40, 50}));
  EXPECT_EQ(signal.trace.channels[1], (std::vector<double>{1, 2, 3, 4, 5}));
  EXPECT_NEAR(signal.trace.end(), 0.112, 1e-15);
}

TEST(SignalCsv, BadFilesNameTheirLineAndColumn) {
  const auto message = [](const std::string& text, const SignalLayout& layout) {
    const auto e = test::thrown<InputError>([&] { parseSignalCsv(text, "t.csv", layout); });
    return e ? std::to_string(e->where().line) + " " + e->where().key + ": " + e->reason() : std::string();
  };
  EXPECT_EQ(message(kTrace, {{"A", "B", "C"}}), "2 C: missing column 'C'");
  EXPECT_EQ(message(kTrace, {{"A"}}), "2 B: unknown column; expected time_s, A");
  EXPECT_EQ(message(kTrace, {{"A", "B"}, 0.001}), "7 time_s: recorded at 333.333 Hz where 1000 Hz is expected");
  EXPECT_EQ(message(kTrace, {{"A", "B"}, 0.0, 6}), "7 time_s: 5 samples, at least 6 needed");
  std::string gap = kTrace;
  gap.replace(gap.find("0.106,3,30\n"), 11, "");
  EXPECT_EQ(message(gap, {{"A", "B"}}), "5 time_s: a step of 6 ms where the file's period is 3 ms: a gap or a change of rate");
  std::string backwards = kTrace;
  backwards.replace(backwards.find("0.109"), 5, "0.105");
  EXPECT_EQ(message(backwards, {{"A", "B"}}), "6 time_s: time does not increase (0.105 s after 0.106 s)");
}

// The trace of kTrace as .npy fields, in the file's order B, A.
NpyRecords traceRecords() {
  return {{"time_s", "B", "A"}, {{0.100, 0.103, 0.106, 0.109, 0.112}, {1, 2, 3, 4, 5}, {10, 20, 30, 40, 50}}};
}

TEST(SignalNpy, ReadsWhatNumPySavesInTheLayoutsOrder) {
  // np.save of np.rec.fromarrays([t, b, a], names="time_s,B,A"): header text and padding as NumPy 1.24 writes them.
  const std::string header = "{'descr': [('time_s', '<f8'), ('B', '<f8'), ('A', '<f8')], 'fortran_order': False, 'shape': (5,), }";
  const std::string bytes = npyRecords(traceRecords());
  ASSERT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(bytes.substr(10, header.size()), header);
  EXPECT_EQ((bytes.size() - 5 * 3 * 8) % 64, 0u);
  EXPECT_EQ(bytes[bytes.size() - 5 * 3 * 8 - 1], '\n');

  const auto signal = parseSignalNpy(bytes, "t.npy", {{"A", "B"}, 0.003});
  EXPECT_EQ(signal.headerLine, 0);
  EXPECT_DOUBLE_EQ(signal.trace.start, 0.1);
  EXPECT_NEAR(signal.trace.period, 0.003, 1e-15);
  EXPECT_EQ(signal.trace.channels[0], (std::vector<double>{10, 20, 30, 40, 50}));
  EXPECT_EQ(signal.trace.channels[1], (std::vector<double>{1, 2, 3, 4, 5}));
}

TEST(SignalNpy, WrittenTracesReadBackBitForBit) {
  const SampledTrace trace{0.25, 1e-4, {{0.1, 0.2, 0.30000000000000004, 0.4}, {-1e-300, 5e300, 3.0, 1.0 / 3.0}}};
  for (const auto format : {SignalFormat::Npy, SignalFormat::Csv}) {
    const auto bytes = signalFile(format, trace, {"X", "A"}, {1.0, 2.0});
    const auto read = format == SignalFormat::Npy ? parseSignalNpy(bytes, "t.npy", {{"X", "A"}}) : parseSignalCsv(bytes, "t.csv", {{"X", "A"}});
    EXPECT_NEAR(read.trace.period, 1e-4, 1e-16);
    for (size_t k = 0; k < 4; ++k) {
      if (format == SignalFormat::Npy) {
        EXPECT_EQ(read.trace.channels[0][k], trace.channels[0][k]);  // bit for bit: no decimal round trip
        EXPECT_EQ(read.trace.channels[1][k], 2.0 * trace.channels[1][k]);
      } else {
        EXPECT_NEAR(read.trace.channels[0][k], trace.channels[0][k], 1e-10 * std::fabs(trace.channels[0][k]));
      }
    }
  }
}

TEST(SignalNpy, BadFilesNameTheirFieldAndRecord) {
  const auto message = [](const std::string& bytes, const SignalLayout& layout = {{"A", "B"}}) {
    const auto e = test::thrown<InputError>([&] { parseSignalNpy(bytes, "t.npy", layout); });
    return e ? e->where().key + ": " + e->reason() : std::string();
  };
  const std::string good = npyRecords(traceRecords());
  const auto withHeader = [&](const std::string& from, const std::string& to) {
    std::string bytes = good;
    bytes.replace(bytes.find(from), from.size(), to + std::string(from.size() - to.size(), ' '));
    return bytes;
  };
  EXPECT_EQ(message("time_s,A\n"), ": not a NumPy .npy file (no \\x93NUMPY magic)");
  std::string version = good;
  version[6] = 4;
  EXPECT_EQ(message(version), ": .npy format version 4 (1, 2 and 3 are read)");
  EXPECT_EQ(message(good.substr(0, good.size() - 8)), "shape: 5 records of 24 bytes, but 112 bytes of data follow the header");
  EXPECT_EQ(message(withHeader("('A', '<f8')", "('A', '<f4')")), "descr.A: type '<f4'; each field must be little-endian float64 ('<f8')");
  EXPECT_EQ(message(withHeader("('A', '<f8')", "('B', '<f8')")), "descr.B: a field name given twice");
  EXPECT_EQ(message(withHeader("(5,), ", "(5,1)")), "shape: the array is not one-dimensional");
  EXPECT_EQ(message(withHeader("'fortran_order': False", "'fortran_order': 0")), "fortran_order: not True or False");
  EXPECT_EQ(message(withHeader("'shape': (5,)", "'shape' (5,)")), "header: expected ':' at byte 91 of the .npy header");
  EXPECT_EQ(message(withHeader("[('time_s', '<f8'), ('B', '<f8'), ('A', '<f8')]", "'<f8'")),
            "descr: a plain array; save a structured array with one named '<f8' field per channel (np.rec.fromarrays)");

  auto records = traceRecords();
  records.columns[2][3] = std::nan("");
  EXPECT_EQ(message(npyRecords(records)), "A[3]: not a finite number");
  records = traceRecords();
  records.columns[0][3] = 0.105;
  EXPECT_EQ(message(npyRecords(records)), "time_s[3]: time does not increase (0.105 s after 0.106 s)");
  EXPECT_EQ(message(good, {{"A", "B", "C"}}), "C: missing column 'C'");
  EXPECT_EQ(message(good, {{"A", "B"}, 0.0, 6}), "time_s[4]: 5 samples, at least 6 needed");
}

}  // namespace
}  // namespace mtacc
