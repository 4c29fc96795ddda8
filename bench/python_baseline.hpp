#pragma once
// Runs a Python baseline script with /usr/bin/python3 at one BLAS thread and returns its
// standard output, or an empty string when it fails.
#include <cstdio>
#include <string>

inline std::string runPythonBaseline(const std::string& arguments) {
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
