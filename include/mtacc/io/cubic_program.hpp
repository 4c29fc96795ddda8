#pragma once
// The cubic machining test as files: its NC program (G-code, axis positions in mm and deg, the
// rotary axes positioned and clamped per zone) and its CL data (zone, tool tip, tool vector).
#include <string>
#include <vector>

#include "mtacc/procedures/cubic_test.hpp"

namespace mtacc {

std::string cubicNcProgram(const Machine& machine, const CubicTestSpec& spec, const std::vector<CubicZonePath>& path);
std::string cubicClData(const CubicTestSpec& spec, const std::vector<CubicZonePath>& path);

}  // namespace mtacc
