#pragma once
// The structure's relative TCP - workpiece displacement in time while its axes accelerate (the
// dynamic geometric error of seed 004 §3.4 from the rigid-body model of seed 000 part II): the
// inertial loads -M E_j a_j(t) on the structure assembled at fixed axis positions, every mode
// with its modal damping integrated exactly for the mean acceleration of each step.
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/dynamics/structure.hpp"

namespace mtacc {

// `accelerations`: one series per structure axis (StructureModel::axes order), m/s^2, sampled
// every `period` s, all of one length; an empty series for an axis that does not move.
// `positions`: the axes' positions (m) at which the structure is assembled. Returns the
// displacement (m, machine frame) at each sample, starting at rest. Throws InputError as
// assembleStructure and undampedModes do, InvalidInput for series of other lengths
// or a period that is not positive and finite.
std::vector<Vec3> accelerationDeflection(const StructureModel& model, const std::vector<double>& positions,
                                         const std::vector<std::vector<double>>& accelerations, double period);

}  // namespace mtacc
