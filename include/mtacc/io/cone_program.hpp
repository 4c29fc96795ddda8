#pragma once
// The cone-frustum test piece as files: its NC program (G-code, axis positions in mm and deg)
// and its CL data (phi, TCP, tool vector, surface normal).
#include <string>

#include "mtacc/procedures/cone.hpp"

namespace mtacc {

std::string coneNcProgram(const Machine& machine, const ConeSpec& spec, const JointMatrix& q, double feed);
std::string coneClData(const ConePath& path);

}  // namespace mtacc
