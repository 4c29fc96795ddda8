// Compensating programs of any length in bounded memory (issue 47): `compensateProgramFile`
// streams a 5-axis program on the tilting table with its full error model from file to file.
// Each run is a child process whose peak resident memory the benchmark reads (wait4's rusage):
// the streamed job at 1,000,000 and 20,000,000 lines (target: peak under 200 MB, the rate of the
// two within 20 %), beside the whole-program path at 1,000,000 lines (the program, its moves,
// its points and the G-code text in memory: parseGcodeProgram, compensateProgram,
// compensatedGcode), whose file must equal the streamed one byte for byte. With --check, the
// same equality at 100,000 lines in-process (a ctest), the deviation figures too.
#include <fmt/format.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "bench_support.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/workflows/compensation.hpp"

using namespace mtacc;

namespace {

// A cone-frustum-like 5-axis finishing program written line by line (never whole in memory):
// every axis moves on every line, block numbers run past 100,000 to 10 * lines, and every
// thousandth line is a comment with a coolant word, every 5000th a full circle in G17 and every
// 7000th a rapid.
void writeProgram(const std::string& path, long long lines) {
  std::ofstream out(path, std::ios::binary);
  std::string block;
  auto it = std::back_inserter(block);
  fmt::format_to(it, "%\n(bench program, {} lines)\nG21 G90 G94\n", lines);
  for (long long i = 3; i < lines - 1; ++i) {
    const double t = 200.0 * M_PI * static_cast<double>(i) / static_cast<double>(lines);
    const double x = 150 * std::sin(t / 7), y = 100 * std::cos(t / 5);
    if (i % 1000 == 0) {
      fmt::format_to(it, "N{} (section {}) M8\n", 10 * i, i / 1000);
    } else if (i % 5000 == 1) {
      fmt::format_to(it, "N{} G2 I{:.4f} J0 F1500\n", 10 * i, x > 0 ? -5.0 : 5.0);
    } else {
      fmt::format_to(it, "N{} {} X{:.4f} Y{:.4f} Z{:.4f} B{:.4f} C{:.4f}{}\n", 10 * i, i % 7000 == 2 ? "G0" : "G1", x, y,
                     50 + 80 * std::sin(t / 11), -20 - 40 * (0.5 + 0.5 * std::sin(t / 13)), std::fmod(t / 3 / kDeg, 360.0),
                     i == 3 || i % 7000 == 3 ? " F2000" : "");
    }
    if (block.size() > (1u << 20)) {
      out << block;
      block.clear();
    }
  }
  out << block << "M30\n";
}

std::string slurp(const std::string& path) { return readTextFile(path); }

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// `job` in a child process: its wall time and peak resident memory (MB); it exits 1 on an error.
struct Run {
  double seconds = 0.0, peakMb = 0.0;
  bool ok = false;
};
Run inChild(const std::function<void()>& job) {
  const double t0 = now();
  const pid_t pid = fork();
  if (pid == 0) {
    try {
      job();
    } catch (const std::exception& e) {
      fmt::print(stderr, "bench_program_streaming: {}\n", e.what());
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  return {now() - t0, static_cast<double>(usage.ru_maxrss) / 1024.0, WIFEXITED(status) && WEXITSTATUS(status) == 0};
}

ProgramCompensationRequest request(const std::string& in, const std::string& out) {
  ProgramCompensationRequest r;
  r.programFile = in;
  r.outputFile = out;
  return r;
}

// The whole-program path: the same program, its compensation, its check and G-code held in memory,
// with the streamed file's header (its figures are the streamed run's).
std::string wholeProgram(const MachineSetup& setup, const std::string& in, const std::string& header, ProgramDeviation& deviation) {
  const GcodeProgram program = readGcodeProgram(in, *setup.machine);
  const CompensatedProgram c = compensateProgram(setup.machine, setup.errors, program);
  deviation = programDeviation(setup.machine, setup.errors, program, c.points);
  return compensatedGcode(*setup.machine, program, c, header);
}

// The header the streamed file holds: its comment lines after the '%', unbracketed.
std::string headerOf(const std::string& gcode) {
  std::istringstream in(gcode);
  std::string line, header;
  std::getline(in, line);  // %
  while (std::getline(in, line) && line.starts_with('(')) {
    if (!header.empty()) header += '\n';
    header.append(line, 1, line.size() - 2);
  }
  return header;
}

}  // namespace

int main(int argc, char** argv) {
  const bool check = bench::agreementCheckOnly(argc, argv);
  const auto machine = std::make_shared<const Machine>(loadMachine("tilting-table"));
  const MachineSetup setup{machine, loadMachineErrors(*machine), std::nullopt};
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("mtacc-bench-streaming-{}", ::getpid());
  std::filesystem::create_directories(dir);
  const auto file = [&](const std::string& name) { return (dir / name).string(); };
  int status = 0;

  if (check) {
    writeProgram(file("in.nc"), 100'000);
    const auto r = compensateProgramFile(setup, request(file("in.nc"), file("streamed.nc")));
    const std::string streamed = slurp(file("streamed.nc"));
    ProgramDeviation whole;
    const bool same = wholeProgram(setup, file("in.nc"), headerOf(streamed), whole) == streamed;
    const bool sameDeviation = whole.after.maxPosition == r.deviation.after.maxPosition && whole.before.rmsPosition == r.deviation.before.rmsPosition &&
                               whole.after.samples == r.deviation.after.samples;
    const long long lastNumber = 10 * (100'000 - 2);  // block numbers past 100,000 kept as written
    const std::string last = fmt::format("\nN{} ", lastNumber);
    fmt::print("100,000 lines (N to {}): streamed file {} the whole-program path's byte for byte ({} bytes); deviation figures {}\n",
               lastNumber, same ? "equals" : "DIFFERS FROM", streamed.size(), sameDeviation ? "equal" : "DIFFER");
    status = same && sameDeviation && streamed.find(last) != std::string::npos ? 0 : 1;
  } else {
    struct Size {
      long long lines;
      Run streamed;
    };
    std::vector<Size> sizes{{1'000'000, {}}, {20'000'000, {}}};
    Run whole;
    for (auto& s : sizes) {
      const double t0 = now();
      writeProgram(file("in.nc"), s.lines);
      fmt::print("{} lines written in {:.1f} s ({:.0f} MB)\n", s.lines, now() - t0, std::filesystem::file_size(file("in.nc")) / 1e6);
      s.streamed = inChild([&] { compensateProgramFile(setup, request(file("in.nc"), file("streamed.nc"))); });
      fmt::print("  streamed: {:.1f} s, {:.0f} lines/s, peak resident {:.1f} MB\n", s.streamed.seconds, s.lines / s.streamed.seconds,
                 s.streamed.peakMb);
      if (s.lines == 1'000'000) {
        const std::string header = headerOf(slurp(file("streamed.nc")));
        whole = inChild([&] {
          ProgramDeviation deviation;
          writeFileAtomically(file("whole.nc"), wholeProgram(setup, file("in.nc"), header, deviation));
        });
        const bool same = whole.ok && slurp(file("whole.nc")) == slurp(file("streamed.nc"));
        fmt::print("  whole program in memory (the path before streaming): {:.1f} s, peak resident {:.1f} MB; the files {}\n", whole.seconds,
                   whole.peakMb, same ? "are equal byte for byte" : "DIFFER");
        if (!same) status = 1;
        std::filesystem::remove(file("whole.nc"));
      }
      std::filesystem::remove(file("streamed.nc"));
      if (!s.streamed.ok) status = 1;
    }
    const double rate1 = 1e6 / sizes[0].streamed.seconds, rate20 = 2e7 / sizes[1].streamed.seconds;
    const double peak = std::max(sizes[0].streamed.peakMb, sizes[1].streamed.peakMb);
    fmt::print("rate at 20M lines against 1M: {:.3f} (target within 0.8 to 1.2); peak resident {:.1f} MB (target under 200 MB); "
               "memory at 1M lines, whole program against streamed: {:.1f}x\n",
               rate20 / rate1, peak, whole.peakMb / sizes[0].streamed.peakMb);
    if (std::abs(rate20 / rate1 - 1.0) > 0.2 || peak >= 200.0) status = 1;
  }
  std::filesystem::remove_all(dir);
  return status;
}
