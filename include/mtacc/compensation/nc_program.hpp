#pragma once
// An NC program in axis positions as mtacc holds it once read (io/gcode_program reads G-code into
// it): its moves, each as the controller interpolates it, and per line what the compensated
// program keeps of it.
#include <string>
#include <vector>

#include <boost/container/small_vector.hpp>

namespace mtacc {

// A move's axis positions, held in the move itself up to six axes: a million-line program
// allocates nothing per move.
using AxisPositions = boost::container::small_vector<double, 6>;

enum class MotionMode { Rapid, Linear, ArcClockwise, ArcCounterClockwise };

struct GcodeMove {
  int line = 0;                   // 1-based line in the file
  MotionMode mode = MotionMode::Linear;
  AxisPositions from, to;         // commanded axes, mm and rad, absolute
  double feed = 0.0;              // mm/min; 0 for rapids
  double toolLength = 0.0;        // mm: the active G43 length, added to the machine's tool along its direction
  // Arcs: the centre in the plane's two linear axes (absolute, mm), the plane's axis indices
  // (first, second, normal; e.g. X, Y, Z for G17) and the signed angle swept (rad, > 0 counter-
  // clockwise seen from the normal's positive side); the normal axis moves linearly (helix).
  double centre[2] = {0.0, 0.0};
  int planeAxes[3] = {0, 1, 2};
  double sweep = 0.0;

  bool isArc() const { return mode == MotionMode::ArcClockwise || mode == MotionMode::ArcCounterClockwise; }
  // The commands at s in [0, 1] along the move as the controller interpolates it: linearly in
  // every axis, or along the arc (angle proportional to s).
  std::vector<double> at(double s) const;
  void at(double s, std::vector<double>& q) const;  // the same into q, its storage reused along a program
  // Each commanded axis's direction of motion at s (+1, -1; 0 where it stands, as at an arc's
  // quadrant point), for the reversal errors of the machine on its way.
  std::vector<int> motion(double s) const;
  // The same as the machine's reversal errors see it: `held` holds the directions before (empty
  // at the program's start) and becomes those at s, an axis standing keeping the side it last
  // moved to (its backlash stays taken up); 0 only until the axis first moves.
  void heldMotion(double s, std::vector<int>& held) const;
  // Where along the move (0 < s < 1) an axis reverses: an arc's quadrant points.
  std::vector<double> reversals() const;
  // Arcs: the radius at the start (mm).
  double radius() const;
};

// One line of the file: its text without the motion, for the writer, and its moves' indices.
struct GcodeLine {
  int number = 0;        // 1-based
  std::vector<std::string> kept;  // the words and comments that stay, as written, in their order
  std::string sequence;  // its N word ("N120"), or ""
  int move = -1;         // index into moves, or -1
};

struct GcodeProgram {
  std::string file;
  std::vector<GcodeLine> lines;
  std::vector<GcodeMove> moves;
};

}  // namespace mtacc
