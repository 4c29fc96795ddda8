#include "bench_support.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <string_view>

namespace mtacc::bench {

bool agreementCheckOnly(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--check") {
      fmt::print("--check: the agreement check at a small size; the times printed are not the benchmark's "
                 "(scripts/bench.sh runs it at full size)\n");
      return true;
    }
  return false;
}

std::string benchDir() { return MTACC_BENCH_DIR; }
std::string pythonBuildDir() { return MTACC_PYTHON_DIR; }

std::string runPythonBaseline(const std::string& arguments) {
  const std::string cmd = "OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 /usr/bin/python3 " + arguments;
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, n);
    if (::pclose(p) != 0) out.clear();
  }
  return out;
}

}  // namespace mtacc::bench
