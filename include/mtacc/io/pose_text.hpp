#pragma once
// Axis values written as text on a command line or in a Python call: "X=10,Y=0,B=-15" (mm and
// deg), "X=5um,B=10urad" (quantities with units) and "X=1ms" (times).
#include <string>
#include <vector>

#include "mtacc/machine/machine.hpp"

namespace mtacc {

// One value per commanded axis, mm and rad. Every commanded axis must be named unless
// `partial` (the others are then zero). Throws InputError naming `key` and the axis.
std::vector<double> parsePose(const Machine& machine, const std::string& text, const std::string& key, bool partial = false);
// Per commanded axis: a length for linear and an angle for rotary axes, with units (mm, rad);
// axes not named are zero; empty text gives an empty vector.
std::vector<double> parseAxisQuantities(const Machine& machine, const std::string& text, const std::string& key);
// Per commanded axis: a time in s or ms (s); empty text gives an empty vector.
std::vector<double> parseAxisTimes(const Machine& machine, const std::string& text, const std::string& key);

}  // namespace mtacc
