#pragma once
// A machined surface (height map) as files other software opens: a CSV matrix of heights, a
// NumPy .npy array, a PLY or binary STL triangle surface, and a colour map as PNG or as SVG
// (the PNG with the zones, their mean heights and a colour bar). Heights in the files are mm
// in the workpiece frame unless stated.
#include <string>
#include <vector>

#include "mtacc/procedures/zone_planes.hpp"

namespace mtacc {

// One row per grid row (y ascending), heights relative to the nominal face in um, with the
// grid in comment lines.
std::string heightMapCsv(const HeightMap& map);
// float32 array (ny, nx), heights relative to the nominal face in mm.
std::string heightMapNpy(const HeightMap& map);
// Every `stride`-th cell as a vertex (absolute z), two triangles per grid square.
std::string heightMapPly(const HeightMap& map, int stride);
std::string heightMapStl(const HeightMap& map, int stride);
// The stride that keeps an exported surface within `vertices` vertices.
int exportStride(const HeightGrid& grid, long vertices = 1000000);

struct ColourMap {
  double limit = 0.01;  // mm: -limit blue, 0 white, +limit red
  int pixels = 1200;    // largest side; cells are averaged down to it
};
// The map's heights (relative to its reference) as an RGB image, y up.
std::string heightMapPng(const HeightMap& map, const ColourMap& colours);
// The PNG framed with axes in mm, each zone outlined with its name and mean height (um), and
// a colour bar; `title` above.
std::string zoneMapSvg(const HeightMap& map, const ColourMap& colours, const CubicTestSpec& spec,
                       const std::vector<ZonePlane>& zones, const std::string& title);

}  // namespace mtacc
