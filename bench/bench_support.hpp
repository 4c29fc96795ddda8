#pragma once
// What every benchmark shares: its two sizes, where its baseline scripts are, and how it runs
// them.
#include <string>

namespace mtacc::bench {

// True when the benchmark was started with --check: the agreement of mtacc's answer and the
// baseline's alone, at a small size and one repetition (a ctest: a wrong answer or a broken
// baseline fails the test suite). Its times are not the benchmark's and are printed as such.
// Without it, the full benchmark (scripts/bench.sh).
bool agreementCheckOnly(int argc, char** argv);

std::string benchDir();        // bench/ of the source tree: the baseline scripts and data
std::string pythonBuildDir();  // the build tree's Python package folder

// Runs a Python baseline script with /usr/bin/python3 at one BLAS thread and returns its
// standard output, or an empty string when it fails.
std::string runPythonBaseline(const std::string& arguments);

}  // namespace mtacc::bench
