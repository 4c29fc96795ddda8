#pragma once
// HEIDENHAIN nonlinear axis error compensation: per input axis a compensation-value table (*.COM)
// whose AXISPOS column holds the compensation points (mm, from the machine datum) and whose other
// columns, named after the axes, hold the values of the axes that depend on it; the assignment
// table (*.CMA) enters each *.COM in the column of its input axis, the line active with '*'
// (MANUALplus 620 technical manual, "Entering compensation values", "Assigning the compensation
// value tables to the axes"). Written in the control's table form: "BEGIN <name> MM", the column
// header, one row per point numbered in NR, "[END]".
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "mtacc/compensation/correction_tables.hpp"

namespace mtacc {

// The one-axis functions as "heidenhain-<input>.com" files (at most 256 points each: the TNC
// refuses more) and "heidenhain.cma" naming them; values in mm, the correction added to the
// column's axis. An input axis with reversal trims (`trims`, at the functions' points; empty for
// none) gets the BACKLASH column: "the compensation values measured in the negative direction of
// traverse" (p. 716), its own column then holding those of the positive direction. Throws
// InputError for a function with more than 256 points.
std::vector<std::pair<std::string, std::string>> heidenhainTables(const OneAxisReduction& reduction, const std::array<ReversalTrims, 3>& trims = {});

}  // namespace mtacc
