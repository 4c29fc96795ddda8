#include "mtacc/procedures/machined_surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec3 cutterPoint(const KinematicModel& model, const double* q, const int* dir, const CuttingTool& tool, Vec3& axis) {
  const ToolPoint t = toolPoint(model, q, dir);
  axis = t.direction;
  return tool.shape == ToolShape::Ball ? Vec3(t.position + tool.radius * t.direction) : t.position;
}

// Appends the actual path of the commanded straight move qa -> qb (qa's point already in the
// path), halving it until the path departs from each chord by less than the tolerance.
struct MoveTracer {
  const KinematicModel& model;
  const CuttingTool& tool;
  const int* dir;
  double tolerance;
  CutterPath& out;

  void trace(const Eigen::VectorXd& qa, const Vec3& pa, const Eigen::VectorXd& qb, const Vec3& pb, const Vec3& axisB,
             int depth) {
    const Eigen::VectorXd qm = 0.5 * (qa + qb);
    Vec3 axisM;
    const Vec3 pm = cutterPoint(model, qm.data(), dir, tool, axisM);
    if (depth < 24 && (pm - 0.5 * (pa + pb)).norm() > tolerance) {
      if (out.points.size() >= kMaxCutterPoints)
        throw InputError(InputLocation{"", 0, "chord_tolerance"},
                         fmt::format("the actual path needs more than {} points to follow its chords within {:g} mm; "
                                     "allow a larger chord tolerance",
                                     kMaxCutterPoints, tolerance));
      trace(qa, pa, qm, pm, axisM, depth + 1);
      trace(qm, pm, qb, pb, axisB, depth + 1);
      return;
    }
    out.points.push_back(pb);
    out.axes.push_back(axisB);
  }
};

// 2-D distance from p to the segment a-b.
double segmentDistance(double px, double py, const Vec3& a, const Vec3& b) {
  const double dx = b.x() - a.x(), dy = b.y() - a.y(), l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((px - a.x()) * dx + (py - a.y()) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = px - a.x() - t * dx, ey = py - a.y() - t * dy;
  return std::sqrt(ex * ex + ey * ey);
}

// A move prepared for pruning and evaluation.
struct Move {
  Vec3 a, b, axis;
  double zMin, zMax;
};

double lowerBound(const CuttingTool& tool, const Move& m, double dNear) {
  if (tool.shape == ToolShape::Ball) return dNear < tool.radius ? m.zMin - std::sqrt(tool.radius * tool.radius - dNear * dNear) : kInf;
  return dNear < tool.radius ? m.zMin - tool.radius * std::hypot(m.axis.x(), m.axis.y()) : kInf;
}

double upperBound(const CuttingTool& tool, const Move& m, double dFar) {
  if (tool.shape == ToolShape::Ball) return dFar <= tool.radius ? m.zMax - std::sqrt(tool.radius * tool.radius - dFar * dFar) : kInf;
  return dFar <= tool.radius * m.axis.z() ? m.zMax + tool.radius * std::hypot(m.axis.x(), m.axis.y()) : kInf;
}

class TileCutter {
 public:
  TileCutter(HeightMap& map, const CuttingTool& tool, const std::vector<Move>& moves, double stock)
      : map_(map), tool_(tool), moves_(moves), stock_(stock), scratch_(kMaxDepth) {}

  // Cuts the tile of cells [i0, i1) x [j0, j1) with the candidate moves; the tile's disc of
  // radius rho about its centre bounds each move's distance, and tiles are split in four
  // until few cells or a single candidate remain.
  void cut(int i0, int i1, int j0, int j1, const std::vector<int>& candidates, size_t depth = 0) {
    const HeightGrid& g = map_.grid;
    const double cx = 0.5 * (g.x(i0) + g.x(i1 - 1)), cy = 0.5 * (g.y(j0) + g.y(j1 - 1));
    const double rho = 0.5 * g.spacing * std::hypot(i1 - i0 - 1, j1 - j0 - 1);
    // A move below which every cell ends (the lowest upper bound) is kept, so a move whose lower
    // bound lies above that is pruned; one that cannot go below the stock is pruned too.
    double covered = INFINITY;
    auto& [lower, kept] = scratch_[depth];
    lower.resize(candidates.size());
    kept.clear();
    for (size_t k = 0; k < candidates.size(); ++k) {
      const Move& m = moves_[static_cast<size_t>(candidates[k])];
      const double d = segmentDistance(cx, cy, m.a, m.b);
      lower[k] = lowerBound(tool_, m, std::max(0.0, d - rho));
      covered = std::min(covered, upperBound(tool_, m, d + rho));
    }
    for (size_t k = 0; k < candidates.size(); ++k)
      if (lower[k] < stock_ && lower[k] <= covered) kept.push_back(candidates[k]);
    if (kept.empty()) return;
    if ((i1 - i0) * (j1 - j0) <= 16 || kept.size() == 1) {
      evaluate(i0, i1, j0, j1, kept);
      return;
    }
    const int im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1, jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
    for (const auto& [a0, a1] : {std::pair{i0, im}, std::pair{im, i1}})
      for (const auto& [b0, b1] : {std::pair{j0, jm}, std::pair{jm, j1}})
        if (a0 < a1 && b0 < b1) cut(a0, a1, b0, b1, kept, depth + 1);
  }

 private:
  void evaluate(int i0, int i1, int j0, int j1, const std::vector<int>& kept) {
    const HeightGrid& g = map_.grid;
    for (int j = j0; j < j1; ++j) {
      const double y = g.y(j);
      float* row = map_.height.data() + static_cast<size_t>(j) * static_cast<size_t>(g.nx);
      for (int i = i0; i < i1; ++i) {
        const double x = g.x(i);
        double lowest = kInf;
        for (int k : kept) {
          const Move& m = moves_[static_cast<size_t>(k)];
          lowest = std::min(lowest, sweptToolBottom(tool_, m.a, m.b, m.axis, x, y));
        }
        // Only a lower height is written, so an untouched cell keeps its value to the bit.
        if (lowest - map_.reference < row[i]) row[i] = static_cast<float>(lowest - map_.reference);
      }
    }
  }

  HeightMap& map_;
  const CuttingTool& tool_;
  const std::vector<Move>& moves_;
  double stock_;  // the highest cell before cutting
  // Per depth of the recursion: sized once, so that a deeper level never moves a shallower
  // level's buffers. Root tiles of 64 x 64 cells split in four reach depth 5.
  static constexpr size_t kMaxDepth = 8;
  std::vector<std::pair<std::vector<double>, std::vector<int>>> scratch_;
};

double ballBottom(double r, const Vec3& a, const Vec3& b, double x, double y) {
  const double qx = x - a.x(), qy = y - a.y();
  const double dx = b.x() - a.x(), dy = b.y() - a.y(), dz = b.z() - a.z();
  const double horizontal = dx * dx + dy * dy, l2 = horizontal + dz * dz, q2 = qx * qx + qy * qy;
  if (horizontal > 1e-24 * (1 + l2)) {
    // The vertical line meets the infinite cylinder of radius r about the move where
    // horizontal h^2 - 2 s dz h + q2 l2 - s^2 - r^2 l2 = 0 (h = z - a.z, s = q . d).
    const double s = qx * dx + qy * dy;
    const double half = -s * dz, c = q2 * l2 - s * s - r * r * l2;
    const double disc = half * half - horizontal * c;
    if (disc >= 0) {
      const double h = (-half - std::sqrt(disc)) / horizontal;
      const double t = s + h * dz;  // projection on the move, times l2
      if (t >= 0 && t <= l2) return a.z() + h;
    }
  }
  double z = kInf;
  if (q2 <= r * r) z = a.z() - std::sqrt(r * r - q2);
  const double px = x - b.x(), py = y - b.y(), p2 = px * px + py * py;
  if (p2 <= r * r) z = std::min(z, b.z() - std::sqrt(r * r - p2));
  return z;
}

double discBottom(double r, const Vec3& a, const Vec3& b, const Vec3& v, double x, double y) {
  // The disc centred at c(t) = a + t (b - a) with normal v meets the vertical line at
  // z(t) = c_z - ((x - c_x) v_x + (y - c_y) v_y) / v_z; the offset e(t) = e0 + t e1 from the
  // centre must be within r. Both are linear in t, so the lowest point is at an end of the
  // interval of t where |e(t)| <= r.
  const Vec3 d = b - a;
  const auto offset = [&](double ex, double ey) { return Vec3(ex, ey, -(ex * v.x() + ey * v.y()) / v.z()); };
  const Vec3 e0 = offset(x - a.x(), y - a.y());
  const Vec3 e1 = offset(-d.x(), -d.y());
  const double qa = e1.squaredNorm(), qb = e0.dot(e1), qc = e0.squaredNorm() - r * r;
  double t0 = 0, t1 = 1;
  if (qa < 1e-24) {
    if (qc > 0) return kInf;
  } else {
    const double disc = qb * qb - qa * qc;
    if (disc < 0) return kInf;
    const double root = std::sqrt(disc);
    t0 = std::max(0.0, (-qb - root) / qa);
    t1 = std::min(1.0, (-qb + root) / qa);
    if (t0 > t1) return kInf;
  }
  const auto z = [&](double t) { return a.z() + t * d.z() + e0.z() + t * e1.z(); };
  return std::min(z(t0), z(t1));
}

}  // namespace

CutterPath cutterPath(const KinematicModel& model, const std::vector<CubicZonePath>& path, const CuttingTool& tool,
                      double chordTolerance) {
  CutterPath out;
  out.tool = tool;
  for (const auto& zone : path) {
    out.starts.push_back(out.points.size());
    for (Eigen::Index i = 0; i < zone.q.rows(); ++i) {
      const int* dir = zone.direction.row(i).data();
      const Eigen::VectorXd qb = zone.q.row(i).transpose();
      Vec3 axisB;
      const Vec3 pb = cutterPoint(model, qb.data(), dir, tool, axisB);
      if (i == 0) {
        out.points.push_back(pb);
        out.axes.push_back(axisB);
        continue;
      }
      const Eigen::VectorXd qa = zone.q.row(i - 1).transpose();
      Vec3 axisA;
      const Vec3 pa = cutterPoint(model, qa.data(), dir, tool, axisA);
      // A reversal error moves the tool where an axis turns: the move starts from there.
      if ((pa - out.points.back()).norm() > 1e-12) {
        out.points.push_back(pa);
        out.axes.push_back(axisA);
      }
      MoveTracer{model, tool, dir, chordTolerance, out}.trace(qa, pa, qb, pb, axisB, 0);
    }
  }
  return out;
}

HeightGrid squareGrid(double size, double spacing, const std::string& key, double cx, double cy) {
  if (!(spacing >= 1e-4 && spacing <= size))
    throw InputError(InputLocation{"", 0, key}, fmt::format("the grid spacing must be in [0.0001 mm, {:g} mm]", size));
  const double n = std::ceil(size / spacing - 1e-9);
  if (n * n > 3e9)
    throw InputError(InputLocation{"", 0, key},
                     fmt::format("{:g} mm at {:g} mm gives {:.3g} cells (12 GB); at most 3e9 cells", size, spacing, n * n));
  HeightGrid g;
  g.spacing = spacing;
  g.nx = g.ny = static_cast<int>(n);
  g.x0 = cx - 0.5 * n * spacing;
  g.y0 = cy - 0.5 * n * spacing;
  return g;
}

HeightMap stockHeightMap(const HeightGrid& grid, double reference, double stock) {
  return HeightMap{grid, reference, std::vector<float>(grid.cells(), static_cast<float>(stock))};
}

double sweptToolBottom(const CuttingTool& tool, const Vec3& a, const Vec3& b, const Vec3& axis, double x, double y) {
  return tool.shape == ToolShape::Ball ? ballBottom(tool.radius, a, b, x, y) : discBottom(tool.radius, a, b, axis, x, y);
}

void cutHeightMap(HeightMap& map, const CutterPath& path, int threads) {
  const HeightGrid& g = map.grid;
  std::vector<Move> moves;
  for (size_t p = 0; p < path.starts.size(); ++p) {
    const size_t end = p + 1 < path.starts.size() ? path.starts[p + 1] : path.points.size();
    for (size_t i = path.starts[p] + 1; i < end; ++i) {
      const Vec3 &a = path.points[i - 1], &b = path.points[i];
      moves.push_back({a, b, path.axes[i - 1], std::min(a.z(), b.z()), std::max(a.z(), b.z())});
    }
  }
  // Root tiles of 64 x 64 cells, each with the moves whose reach overlaps it.
  constexpr int kTile = 64;
  const int tx = (g.nx + kTile - 1) / kTile, ty = (g.ny + kTile - 1) / kTile;
  std::vector<std::vector<int>> tiles(static_cast<size_t>(tx) * static_cast<size_t>(ty));
  const double reach = path.tool.radius, tileSize = kTile * g.spacing;
  for (size_t k = 0; k < moves.size(); ++k) {
    const Move& m = moves[k];
    const auto index = [&](double v, double origin, int n) {
      return std::clamp(static_cast<int>(std::floor((v - origin) / tileSize)), 0, n - 1);
    };
    const double xl = std::min(m.a.x(), m.b.x()) - reach, xh = std::max(m.a.x(), m.b.x()) + reach;
    const double yl = std::min(m.a.y(), m.b.y()) - reach, yh = std::max(m.a.y(), m.b.y()) + reach;
    if (xh < g.x0 || yh < g.y0 || xl > g.x0 + g.nx * g.spacing || yl > g.y0 + g.ny * g.spacing) continue;
    for (int j = index(yl, g.y0, ty); j <= index(yh, g.y0, ty); ++j)
      for (int i = index(xl, g.x0, tx); i <= index(xh, g.x0, tx); ++i)
        tiles[static_cast<size_t>(j) * static_cast<size_t>(tx) + static_cast<size_t>(i)].push_back(static_cast<int>(k));
  }
  const double stock = map.reference + *std::max_element(map.height.begin(), map.height.end());
  parallelFor(static_cast<long>(tiles.size()), threads, [&](long begin, long end) {
    TileCutter cutter(map, path.tool, moves, stock);
    for (long t = begin; t < end; ++t) {
      const int i = static_cast<int>(t % tx), j = static_cast<int>(t / tx);
      cutter.cut(i * kTile, std::min(g.nx, (i + 1) * kTile), j * kTile, std::min(g.ny, (j + 1) * kTile),
                 tiles[static_cast<size_t>(t)]);
    }
  });
}

}  // namespace mtacc
