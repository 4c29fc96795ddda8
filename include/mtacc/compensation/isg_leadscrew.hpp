#pragma once
// TwinCAT/ISG leadscrew error compensation (LSEC, kw.ssfk.*) in an axis's compensation value
// list, bilateral: a table for each direction of motion, which "can also compensate any backlash"
// (ISG kernel documentation, FCT-C5). Each value is the error as measured, actual less programmed
// position (its example: 19866.7 um programmed, 19856.5 um reached moving positive: -102), in
// 0.1 um (0.0001 degrees on a rotary axis); the positions are set out one by one (interval 0).
#include <string>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// The list of one axis's reversal: the trims added moving positive and moving negative, written as
// the errors they correct (negated), to be loaded beside the volumetric compensation, which holds
// the axis's error standing. Its logical axis number is the axis's place in the machine file.
std::string isgLeadscrewList(const Machine& machine, const AxisReversalTable& reversal);

// The unit of the list's values and positions, mm (or degrees): what its whole numbers count.
inline constexpr double kIsgLeadscrewUnit = 1e-4;

}  // namespace mtacc
