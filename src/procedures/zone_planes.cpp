#include "mtacc/procedures/zone_planes.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::vector<ZonePlane> zonePlanes(const HeightMap& map, const CubicTestSpec& spec, double inset, const HeightMap* baseline) {
  const HeightGrid& g = map.grid;
  if (baseline && baseline->height.size() != map.height.size()) throw InvalidInput("zonePlanes: different grids");
  const double offset = baseline ? map.reference - baseline->reference : 0.0;
  const auto at = [&](int i, int j) { return baseline ? map.at(i, j) - baseline->at(i, j) + offset : map.at(i, j); };
  const double half = spec.zoneSize / 2 - inset;
  if (!(half > 0)) throw InvalidInput("zonePlanes: the inset leaves nothing of the zones");
  std::vector<ZonePlane> planes;
  for (const auto& zone : spec.zones) {
    const int i0 = std::max(0, static_cast<int>(std::ceil((zone.x - half - g.x0) / g.spacing - 0.5)));
    const int i1 = std::min(g.nx, static_cast<int>(std::floor((zone.x + half - g.x0) / g.spacing - 0.5)) + 1);
    const int j0 = std::max(0, static_cast<int>(std::ceil((zone.y - half - g.y0) / g.spacing - 0.5)));
    const int j1 = std::min(g.ny, static_cast<int>(std::floor((zone.y + half - g.y0) / g.spacing - 0.5)) + 1);
    // Normal equations of z = c0 + c1 dx + c2 dy, summed row by row.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int j = j0; j < j1; ++j) {
      const double dy = g.y(j) - zone.y;
      double n = 0, sx = 0, sxx = 0, sz = 0, sxz = 0;
      for (int i = i0; i < i1; ++i) {
        const double dx = g.x(i) - zone.x, z = at(i, j);
        if (!std::isfinite(z)) continue;  // a scanned cell without points
        n += 1;
        sx += dx;
        sxx += dx * dx;
        sz += z;
        sxz += dx * z;
      }
      normal += Eigen::Matrix3d{{n, sx, n * dy}, {sx, sxx, sx * dy}, {n * dy, sx * dy, n * dy * dy}};
      rhs += Eigen::Vector3d(sz, sxz, sz * dy);
    }
    ZonePlane p;
    p.cells = static_cast<size_t>(std::llround(normal(0, 0)));
    if (p.cells < 3) throw InvalidInput("zone " + zone.name + ": fewer than 3 cells of the grid with a height");
    const Eigen::Vector3d c = normal.ldlt().solve(rhs);
    p.slopeX = c(1);
    p.slopeY = c(2);
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        if (!std::isfinite(at(i, j))) continue;
        const double r = at(i, j) - (c(0) + c(1) * (g.x(i) - zone.x) + c(2) * (g.y(j) - zone.y));
        lo = std::min(lo, r);
        hi = std::max(hi, r);
        sum += at(i, j);
      }
    p.mean = sum / static_cast<double>(p.cells);
    p.residualPeakToValley = hi - lo;
    planes.push_back(p);
  }
  return planes;
}

std::vector<ZonePlane> referencedToZone(const std::vector<ZonePlane>& planes, const CubicTestSpec& spec, size_t reference) {
  const ZonePlane& r = planes.at(reference);
  const CubicZone& rz = spec.zones.at(reference);
  std::vector<ZonePlane> out = planes;
  for (size_t k = 0; k < out.size(); ++k) {
    out[k].mean -= r.at(spec.zones[k].x - rz.x, spec.zones[k].y - rz.y);
    out[k].slopeX -= r.slopeX;
    out[k].slopeY -= r.slopeY;
  }
  return out;
}

size_t referenceZone(const CubicTestSpec& spec) {
  for (size_t k = 0; k < spec.zones.size(); ++k)
    if (spec.zones[k].toolVector.z() > 1 - 1e-12) return k;
  return 0;
}

HeightMap heightDifference(const HeightMap& a, const HeightMap& b) {
  if (a.height.size() != b.height.size()) throw InvalidInput("heightDifference: different grids");
  HeightMap d{a.grid, 0.0, std::vector<float>(a.height.size())};
  const double offset = a.reference - b.reference;
  for (size_t k = 0; k < a.height.size(); ++k)
    d.height[k] = static_cast<float>(static_cast<double>(a.height[k]) - static_cast<double>(b.height[k]) + offset);
  return d;
}

}  // namespace mtacc
