#pragma once
// Finite stiffness (seed 003 §4.2, §5.4): a change of one component error motion that the
// machine's geometry measurement does not hold, because it depends on another axis's position
// (the weight of a moving part) or on the workpiece load. It is a measured table over the
// axis's own position and, optionally, another axis's position, taken at a reference load.
// At load W it is scaled by W / W_ref: seed 003 states no rule in W, and linear is the first
// assumption (reference extraction §5).
#include <vector>

#include <Eigen/Core>

namespace mtacc {

struct StiffnessError {
  int axis = -1;       // whose component error changes (index into Machine::axes)
  int component = 0;   // 0..5 (X Y Z A B C)
  int otherAxis = -1;  // the commanded axis it also depends on; -1: its own position only
  std::vector<double> positions;       // of its own axis, increasing (mm or rad)
  std::vector<double> otherPositions;  // of the other axis, increasing; one entry when otherAxis < 0
  Eigen::MatrixXd values;              // at the reference load: rows = positions, columns = otherPositions
  double referenceLoad = 0.0;          // kg; 0: the change does not depend on the load

  // Linear between the measured positions in both, held constant beyond them (at the reference load).
  double value(double q, double qOther) const;
  // W / W_ref, or 1 when the change does not depend on the load.
  double loadFactor(double load) const { return referenceLoad > 0.0 ? load / referenceLoad : 1.0; }
};

}  // namespace mtacc
