#pragma once
// A program run on a machine with errors, against the path a program was meant to cut (issue
// 45): the check of a compensation against something other than the model that produced it.
// The controller interpolates every feed move (linearly in the axes, or along the arc); the TCP
// and tool direction of the machine with its errors are sampled along it and compared with the
// intended path: the program's own nominal path at the same place of each move, or another
// program's nominal path at its closest point.
#include <memory>
#include <vector>

#include "mtacc/compensation/program_compensation.hpp"

namespace mtacc {

struct BlockDeviation {
  int line = 0;                   // of the program's block
  double maxPosition = 0.0;       // mm
  double maxDirection = 0.0;      // rad
  int samples = 0;
};

struct ProgramPathDeviation {
  PathDeviation total;
  std::vector<BlockDeviation> blocks;  // the feed moves sampled, in program order
  int instantBlocks = 0;               // feed moves of less than 10 um of nominal TCP path, not sampled (a compensated program's steps at reversals)
  double intendedLength = 0.0;         // mm: the intended path's TCP length along its feed moves
};

struct PathDeviationOptions {
  double step = 0.5;  // mm of nominal TCP path between samples (at least 4 samples a move, at most 10000)
};

// `program` run on `errors` against `intended`'s nominal path; intended == nullptr: the
// program's own, at the same s of each move. Against another program the distance is to the
// closest point of its sampled path (chords between its samples), searched in order along it:
// a path that runs the intended one backwards or skips far ahead is measured against the nearest
// stretch found from where it last was. Throws InvalidInput for a step outside
// [1 um, 100 mm] or an intended program without feed moves.
ProgramPathDeviation programPathDeviation(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors,
                                          const GcodeProgram& program, const GcodeProgram* intended,
                                          const PathDeviationOptions& options = {});

}  // namespace mtacc
