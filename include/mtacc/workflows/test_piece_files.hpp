#pragma once
// The files of workflows `cone` and `cubic` that a machine, a CAM check or a viewer reads: each
// written atomically where its path is given, after the study, and named in one line each
// ("NC program written: PATH") for the front ends to show.
#include <string>
#include <vector>

#include "mtacc/workflows/cone_study.hpp"
#include "mtacc/workflows/cubic_test.hpp"

namespace mtacc {

struct ConeFiles {
  std::string gcode;  // the NC program of the path
  std::string cl;     // the CL data: phi, TCP, tool vector, surface normal (CSV)
};
std::vector<std::string> writeConeFiles(const ConeStudy& study, const ConeFiles& files);
// The files named in a `cone` command's values (coneSchema's gcode and cl).
ConeFiles coneFiles(const OptionValues& values);

struct CubicTestFiles {
  std::string gcode, cl;    // the NC program and the CL data (zone, tool tip, tool vector)
  std::string map;          // the deviation referenced to the reference zone: .svg (zones, colour bar) or .png
  std::string mapLimit = "10 um";  // the deviation shown at full colour
  std::string heights;      // the machined heights: .csv (um) or .npy (float32, mm)
  std::string surface;      // the machined surface: .ply or .stl, at most 1e6 vertices
  std::string zonesOut;     // the zone results (heights and tilts) for cubic-identify (CSV)
  std::string scanZonesOut; // the scanned face's zone results, the same form
  std::string traceCl;      // the CL data (tool tip, tool vector) of the recorded axis positions
};
// Throws InputError naming the key (map, heights, surface, map_limit) for a file whose extension
// names no format it can be written in, or a limit out of range: called before the study, so
// that a run that cannot write computes nothing.
void checkCubicTestFiles(const CubicTestFiles& files);
// The files named in a `cubic` command's values (cubicTestSchema's file keys).
CubicTestFiles cubicTestFiles(const OptionValues& values);
std::vector<std::string> writeCubicTestFiles(const CubicTestStudy& study, const CubicTestFiles& files);

}  // namespace mtacc
