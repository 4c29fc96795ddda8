#pragma once
// Compensated NC programs (issue 17, item 2): every point of an axis program is replaced by the
// commands that put the tool, on the machine with its errors, where the program puts it on the
// nominal machine (the inverse error model from the nominal commands plus the previous point's
// correction). Arcs are written as G1 chords and a move is split where the correction varies
// along it, until the written program, interpolated linearly by the controller, stays within
// the tolerance of the nominal path at every segment's midpoint.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mtacc/compensation/nc_program.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"

namespace mtacc {

struct ProgramCompensationOptions {
  double tolerance = 1e-4;           // mm: TCP deviation allowed at a written segment's midpoint (arc chords included)
  double directionTolerance = 5e-6;  // rad: the same for the tool direction (5-axis)
  int maxSplits = 12;                // halvings of one move at most (4096 segments)
  // Each point solved to 0.1 nm and 1 nrad, a hundred times finer than the 10 nm and 1e-5 deg
  // (175 nrad) written.
  ErrorIkOptions ik{{}, 1e-7, 1e-9};
};

// One written point: where it lies on the program's move and the commands written there.
struct CompensatedPoint {
  int move = 0;    // index into GcodeProgram::moves
  double s = 1.0;  // along the move, (0, 1]
  AxisPositions q;  // mm, rad
  double positionResidual = 0.0, directionResidual = 0.0;  // mm, rad: of the inverse error model here
};

// How far the tool strays from the program's nominal path on the machine with its errors:
// TCP (mm) and tool direction (rad), sampled along every written segment.
struct PathDeviation {
  double maxPosition = 0.0;
  double rmsPosition = 0.0;
  double maxDirection = 0.0;
  int samples = 0;
};

// What compensating a program found, accumulated point by point.
struct CompensationSummary {
  std::vector<double> largestCorrection; // per commanded axis, mm or rad
  double largestResidual = 0.0;          // mm: of the inverse error model at a written point
  int notConverged = 0, singular = 0;    // written points
  int firstProblemLine = 0;              // the first line with a point not converged, singular or beyond travel
  std::string travelViolation;           // the first written point beyond travel ("" when none)
  int travelViolationLine = 0;           // and its line
  long long written = 0;                 // points written
};

struct CompensatedProgram : CompensationSummary {
  std::vector<CompensatedPoint> points;  // the start (not written), then the written points in program order; each move's last has s = 1
};

// A program compensated move by move in program order, holding only the points of the move at
// hand: what compensateProgram does for a whole program, in bounded memory for any length.
class ProgramCompensator {
 public:
  ProgramCompensator(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const ProgramCompensationOptions& options = {});
  ~ProgramCompensator();
  // The point before `move` (the program's start, solved from its first move, on the first call),
  // then the points written for it; `index` counts the moves from 0. Valid until the next call.
  std::span<const CompensatedPoint> compensate(const GcodeMove& move, int index);
  const CompensationSummary& summary() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

CompensatedProgram compensateProgram(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                     const ProgramCompensationOptions& options = {});

// The program run on the machine with its errors, sampled at quarters of every written feed
// segment against the program's nominal path at the same place on its move: as written
// (before) and with the commands of `points` interpolated linearly (after). points[0] is the
// start; the rest in program order, as compensateProgram returns them (or read back from its
// G-code).
struct ProgramDeviation {
  PathDeviation before, after;
};
ProgramDeviation programDeviation(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                  const std::vector<CompensatedPoint>& points);
// The same accumulated move by move, as ProgramCompensator gives the points.
class DeviationSum {
 public:
  DeviationSum(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors);  // `errors` outlives it
  ~DeviationSum();
  void add(std::span<const CompensatedPoint> points, const GcodeMove& move);  // the point before the move's, then the move's
  ProgramDeviation result() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// The compensated program as G-code (G21 G90, axis positions in mm and deg, every axis on every
// motion line), with the kept words and comments of every line and a header naming the machine.
std::string compensatedGcode(const Machine& machine, const GcodeProgram& program, const CompensatedProgram& compensated,
                             const std::string& header);
// The same in parts, for a program written as it is compensated: the preamble (a first line of
// '%' alone, the header as comments, G21 G90), then each line with its move's points.
bool isPercentLine(const GcodeLine& line);
std::string compensatedGcodePreamble(const GcodeLine* percent, const std::string& header);
class CompensatedGcodeWriter {
 public:
  explicit CompensatedGcodeWriter(const Machine& machine) : machine_(machine) {}
  // Appends the line to `out`: its kept words, and for a move its points (not the one before).
  void line(std::string& out, const GcodeLine& line, const GcodeMove* move, std::span<const CompensatedPoint> points);

 private:
  const Machine& machine_;
  double feed_ = -1.0;  // the F last written
};

}  // namespace mtacc
