// Programs streamed from file to file (issue 47): the file read a block at a time into the same
// lines as the whole text, the output written as it is produced and put in place only at the end,
// and bad input in the middle of a long program located with nothing left behind. The streamed
// output's equality with the whole-program path, byte for byte at 100,000 lines, is
// BenchmarkAgreement.bench_program_streaming.
#include <fmt/format.h>
#include <gtest/gtest.h>


#include <algorithm>
#include <filesystem>
#include <fstream>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/compensation.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

namespace fs = std::filesystem;

class ProgramStreaming : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name), std::ios::binary) << text; }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  test::TestFolder folder_{"mtacc-streaming"};
  const fs::path dir_ = folder_.dir();
};

// A long 3-axis program, `bad` replacing line `at`.
std::string longProgram(int lines, int at, const std::string& bad) {
  std::string g = "G21 G90 G94 F1000\n";
  for (int i = 2; i <= lines; ++i) g += i == at ? bad + "\n" : fmt::format("N{} G1 X{:.3f} Y{:.3f} Z{:.3f}\n", 10 * i, 100 + (i % 400) * 0.5, 50 + (i % 300) * 0.3, 200 + (i % 97) * 0.2);
  return g;
}

TEST_F(ProgramStreaming, LinesReadABlockAtATimeAreTheWholeTextsLines) {
  // CR LF endings, empty lines, a line longer than the 1 MiB block, no newline at the end.
  const std::string longLine(3 << 20, 'x');
  const std::string text = "first\r\n\nsecond\n" + longLine + "\r\n\r\nlast";
  write("t.txt", text);
  TextLines lines(path("t.txt"));
  std::vector<std::string> read;
  std::string_view line;
  while (lines.next(line)) read.emplace_back(line);
  EXPECT_EQ(read, (std::vector<std::string>{"first", "", "second", longLine, "", "last"}));
  EXPECT_EQ(lines.bytesRead(), text.size());
  EXPECT_EQ(lines.size(), text.size());
  // Nothing after the last newline is not a line; an empty file has none.
  write("u.txt", "a\nb\n");
  TextLines ended(path("u.txt"));
  int count = 0;
  while (ended.next(line)) ++count;
  EXPECT_EQ(count, 2);
  write("empty.txt", "");
  TextLines none(path("empty.txt"));
  EXPECT_FALSE(none.next(line));
  EXPECT_EQ(test::thrown<InputError>([&] { TextLines missing(path("missing.txt")); })->reason(), "no such file");
}

TEST_F(ProgramStreaming, AnOutputIsInPlaceOnlyWhenCommitted) {
  write("out.txt", "before");
  {
    AtomicFile out(path("out.txt"), "out");
    out.write("half");
  }  // an error on the way: destroyed uncommitted
  EXPECT_EQ(readTextFile(path("out.txt")), "before");
  EXPECT_EQ(files(), std::vector<std::string>{"out.txt"});
  AtomicFile body(path("out.txt"), "out"), whole(path("out.txt"), "out");
  body.write(std::string(3 << 20, 'b'));
  whole.write("head\n");
  whole.append(body);
  whole.commit();
  EXPECT_EQ(readTextFile(path("out.txt")), "head\n" + std::string(3 << 20, 'b'));
}

TEST_F(ProgramStreaming, BadInputInTheMiddleGivesItsLineAndNoFile) {
  MachineSetup setup;
  setup.machine = test::bundled("three-axis-vertical");
  setup.errors = loadMachineErrors(*setup.machine);
  ProgramCompensationRequest request;
  request.outputFile = path("out.nc");
  // Past the first MiB written, the parts of the output already on disk.
  for (const auto& [bad, key] : {std::pair<std::string, std::string>{"N300000 G1 X10 Q5", "Q5"}, {"G1 X5000", "X"}, {"G1 X10 (open", "("}}) {
    write("in.nc", longProgram(60'000, 40'000, bad));
    request.programFile = path("in.nc");
    const auto error = test::thrown<InputError>([&] { compensateProgramFile(setup, request); });
    ASSERT_TRUE(error) << bad;
    EXPECT_EQ(error->where().file, path("in.nc"));
    EXPECT_EQ(error->where().line, 40'000) << bad;
    EXPECT_EQ(error->where().key, key) << bad;
    EXPECT_EQ(files(), std::vector<std::string>{"in.nc"}) << bad;
  }
  // The same program without the bad line is compensated, its numbers kept.
  write("in.nc", longProgram(60'000, 0, ""));
  const auto r = compensateProgramFile(setup, request);
  EXPECT_EQ(r.lines, 60'000);
  EXPECT_EQ(r.moves, 59'999);
  const std::string out = readTextFile(path("out.nc"));
  EXPECT_NE(out.find("\nN600000 G1 X"), std::string::npos);
  EXPECT_EQ(files(), (std::vector<std::string>{"in.nc", "out.nc"}));
}

}  // namespace
}  // namespace mtacc
