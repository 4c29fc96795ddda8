#pragma once
// Points probed on a cone-frustum test piece (docs/file-formats.md "Measured cone frustum"): one
// row per point, the element (plane A, cylinder C or the cone), the section it belongs to and its
// coordinates in the CMM's workpiece frame (seed 000 App. A.4.1), mm:
//   element,section,x,y,z
//   plane,A,12.5,-40.1,0.0002
//   cone,z10,48.9996,0.0121,10.0
#include <string>

#include "mtacc/procedures/measured_cone.hpp"

namespace mtacc {

// Throws InputError naming file, line and key: an unknown element, a value not finite or beyond
// 10 m, a section with fewer than four points (the line of its last point), no cone section.
ConePoints parseConePoints(const std::string& text, const std::string& sourceName);
ConePoints readConePoints(const std::string& path);

}  // namespace mtacc
