#pragma once
// A set of recorded tests for the error decomposition of seed 004 (YAML, docs/file-formats.md
// "Decomposition sets"): per feed the command, encoder and instrument signal files, and the
// processing choices (interpolation, clock offset or its search window, reference test, degree,
// the parameter of the motion errors, the drift frame).
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/transform.hpp"
#include "mtacc/core/uniform_spline.hpp"
#include "mtacc/procedures/error_decomposition.hpp"

namespace mtacc {

struct RecordedTest {
  double feed = 0.0;  // mm/min as programmed
  std::string command, encoder, instrument;  // paths, relative ones resolved against the set file's folder
  int line = 0;  // of the test in the set file
};

struct DecompositionSet {
  std::string file;
  std::vector<RecordedTest> tests;
  Vec3 ball = Vec3::Zero();                 // the instrument's workpiece ball centre in the workpiece frame, mm
  double ncPeriod = 0.0;                    // s; 0: as recorded
  double instrumentPeriod = 0.0;            // s; 0: as recorded
  Interpolation interpolation = Interpolation::CubicSpline;
  std::optional<double> clockOffset;        // s; estimated per test when absent
  // s: the most servo lag the traces may show beyond a stated clock offset (where they line up
  // best is the offset plus the lag a pure delay explains; 50 ms is a loop of Kv = 20/s without
  // feed-forward); beyond it, or with the encoder ahead of the command, the offset is doubted.
  double largestLag = 0.05;
  double searchLowest = -0.1, searchHighest = 0.1;  // s
  int referenceTest = 0;                    // index into tests: the given reference feed, else the lowest
  int degree = 20;
  MotionParameter parameter = MotionParameter::Path;
  DriftFrame driftFrame = DriftFrame::Machine;
  ReferenceFit referenceFit = ReferenceFit::Steady;
};
// "machine" or "workpiece" (drift_frame:, decompose --drift-frame); throws InputError at `key`.
DriftFrame parseDriftFrame(const std::string& text, const InputLocation& key);

// Throws InputError naming file, line and key.
DecompositionSet loadDecompositionSet(const std::string& path);
DecompositionSet parseDecompositionSet(const std::string& text, const std::string& sourceName);

}  // namespace mtacc
