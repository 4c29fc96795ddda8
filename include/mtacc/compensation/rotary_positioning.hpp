#pragma once
// A rotary axis's correction of its own command: the angle about its own line by which the
// machine with its errors turns what the axis carries away from where the nominal machine turns
// it, at each position of the axis with the other axes at a pose, negated. The rotary axes' part
// of a positioning table (SINUMERIK LEC, LinuxCNC COMP_FILE on a rotary joint), as the linear
// axes' own-axis functions are theirs.
#include <memory>
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct RotaryPositioning {
  int axis = 0;                  // index into Machine::axes
  std::vector<double> positions;  // rad, equidistant
  // rad, added to the command: standing, moving forward and moving backward (the axis's reversal)
  std::vector<double> standing, forward, reverse;
  bool modulo = false;  // a continuous axis over one turn, its ends equal: the table repeats
  // Standing, linear between the positions; beyond them the end value, or the turn's repeat.
  double correction(double position) const;
};

// For each commanded rotary axis: positions at most 2 degrees apart over its travel (one turn from
// 0 without one; at most 256 positions, LinuxCNC's limit), the other axes at `pose` (all commanded axes, mm and rad). The correction at a
// position solves, to first order, the turn about the axis's own line between the tool and the
// workpiece of the machine with its errors against the nominal machine; turns about other
// directions (the line's tilts, other axes' errors) are not the axis's to correct.
std::vector<RotaryPositioning> rotaryPositioning(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors,
                                                 const std::vector<double>& pose);

}  // namespace mtacc
