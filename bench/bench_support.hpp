#pragma once
// What every benchmark shares: its two sizes, where its baseline scripts are, and how it runs
// them.
#include <string>
#include <vector>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc::bench {

// True when the benchmark was started with --check: the agreement of mtacc's answer and the
// baseline's alone, at a small size and one repetition (a ctest: a wrong answer or a broken
// baseline fails the test suite). Its times are not the benchmark's and are printed as such.
// Without it, the full benchmark (scripts/bench.sh). Either way it first prints the build: the
// instruction sets mtacc was compiled for and the BLAS NumPy runs on this host (the baselines').
bool agreementCheckOnly(int argc, char** argv);

// R-test runs on the tilting table, one per sphere: C turning at B = 0, -30, -60, -90 deg and B
// tilting from 0 to -90 deg at C = 0, 90, 180, 270 deg, each in `steps` steps (40 * steps poses for
// five spheres): the poses of the identification and design benchmarks.
std::vector<MeasurementRun> tiltingTableRTestRuns(const KinematicModel& nominal, int steps, const std::vector<Vec3>& spheres);

// The middle of the times of repeated runs (the upper middle of an even count).
double median(std::vector<double> seconds);

std::string benchDir();        // bench/ of the source tree: the baseline scripts and data
std::string pythonBuildDir();  // the build tree's Python package folder

// Runs a Python baseline script with /usr/bin/python3 at one BLAS thread and returns its
// standard output, or an empty string when it fails.
std::string runPythonBaseline(const std::string& arguments);

}  // namespace mtacc::bench
