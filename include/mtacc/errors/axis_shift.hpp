#pragma once
// Seed 000's convention for a rotary axis's radial error motion (reference §5, Table 3.4): the
// motion t(q) shifts the axis line, so a point p of the turning part goes to t + R(q) (p - t)
// instead of R(q) p + t. The shift acts as the translation (I - R(q)) t, which is what the ISO
// component errors EX, EY, EZ of the axis then hold: written as harmonics over one turn, every
// other part of mtacc evaluates it unchanged.
#include <array>

#include "mtacc/errors/error_model.hpp"

namespace mtacc {

// Adds to errors.motion[0..2] of the rotary axis `axis` the translation of the axis-line shift
// whose X, Y, Z components are `shift` (mm). The shift's terms must be constants or harmonics
// whose period divides a turn (the products with cos q and sin q are then harmonics over a
// turn); anything else throws InvalidInput naming the component.
void addAxisShift(const Machine& machine, int axis, const std::array<ErrorFunction, 3>& shift, AxisErrors& errors);

}  // namespace mtacc
