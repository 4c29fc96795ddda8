// Recorded signals (CSV): channels in the layout's order whatever the file's, the period from
// the time column, and the located errors of a bad file.
#include <gtest/gtest.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/signal_csv.hpp"
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

}  // namespace
}  // namespace mtacc
