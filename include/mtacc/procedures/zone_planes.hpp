#pragma once
// The machined zones evaluated as seed 001 measures them: a least-squares plane over each zone
// (its mean height and in-zone tilt, the scallops averaged out), and the measurement frame
// referenced to a zone (zone I, L239-243). Heights in mm, slopes in mm/mm.
#include <vector>

#include "mtacc/procedures/machined_surface.hpp"

namespace mtacc {

struct ZonePlane {
  double mean = 0;             // mean height over the evaluated cells (for a plane: its value at the zone centre)
  double slopeX = 0, slopeY = 0;
  double residualPeakToValley = 0;  // of the surface about the plane
  size_t cells = 0;

  double at(double dx, double dy) const { return mean + slopeX * dx + slopeY * dy; }
};

// The plane of each zone over its square shrunk by `inset` on every side (the neighbours'
// tools overcut the edges), of `heights` less `baseline` (same grid) when one is given — the
// difference of two surfaces without a third map in memory.
std::vector<ZonePlane> zonePlanes(const HeightMap& heights, const CubicTestSpec& spec, double inset,
                                  const HeightMap* baseline = nullptr);

// The planes in the measurement frame of seed 001 (L239): the plane of zone `reference`
// subtracted from every zone.
std::vector<ZonePlane> referencedToZone(const std::vector<ZonePlane>& planes, const CubicTestSpec& spec, size_t reference);

// The index of the zone the measurement is referenced to: the first zone cut with the tool
// normal to the face (zone I), else the first zone.
size_t referenceZone(const CubicTestSpec& spec);

// a - b, cell by cell (same grid).
HeightMap heightDifference(const HeightMap& a, const HeightMap& b);

}  // namespace mtacc
