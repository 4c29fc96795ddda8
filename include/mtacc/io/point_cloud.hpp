#pragma once
// A scanned surface as the points a scanner or another program gives (docs/file-formats.md
// "Scanned surfaces"): a CSV with x,y,z columns, a PLY (ASCII or binary little-endian; its
// vertices' x, y, z, float or double) or an STL (binary or ASCII; its triangles' corners, each
// once). mm, the workpiece frame.
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"

namespace mtacc {

// By the file's extension (.csv, .ply, .stl; any case). Throws InputError naming the file and
// the line (CSV, ASCII) or the vertex (binary): a value that is not finite or beyond 10 m, a
// header that does not describe x, y, z, a file cut short, more than 50 million points.
std::vector<Vec3> readPointCloud(const std::string& path);
// The same from the file's contents, its form named by `extension` ("csv", "ply", "stl").
std::vector<Vec3> parsePointCloud(const std::string& bytes, const std::string& extension, const std::string& sourceName);

}  // namespace mtacc
