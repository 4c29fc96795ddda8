#pragma once
// A machined face as a scanner measures it (seed 001 §5: the zones measured with a surface
// scanner): the scanned points carried onto a height map of the same form as the simulated
// surface's, so that the zones are evaluated by the same zone planes. Lengths in mm.
#include <vector>

#include "mtacc/procedures/machined_surface.hpp"

namespace mtacc {

// Each cell's height is the least-squares plane through the points over it, evaluated at its
// centre (exact for a plane, the mean of the points for points spread evenly about the centre);
// NaN where fewer than three points, or points on one line, fall in the cell (the zone planes
// leave such cells out). Heights relative to `reference` (the nominal face).
HeightMap scannedHeightMap(const std::vector<Vec3>& points, const HeightGrid& grid, double reference);
// Cells of the map with a height.
size_t filledCells(const HeightMap& map);

}  // namespace mtacc
