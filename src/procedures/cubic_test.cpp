#include "mtacc/procedures/cubic_test.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

// Seed 001 Fig. 2 names by grid cell (column, row from the lower left), in the machining order
// of L227.
struct SeedZoneName {
  int column, row;
  const char* name;
};
constexpr SeedZoneName kSeedZones[9] = {{1, 1, "I"},     {0, 1, "II-1"},  {1, 0, "II-2"},  {2, 1, "II-3"}, {1, 2, "II-4"},
                                        {0, 0, "III-1"}, {2, 0, "III-2"}, {2, 2, "III-3"}, {0, 2, "III-4"}};

CubicZone gridZone(int column, int row, int n, double blockSize, double tilt, std::string name) {
  const double size = blockSize / n;
  CubicZone z{std::move(name), -blockSize / 2 + (column + 0.5) * size, -blockSize / 2 + (row + 0.5) * size, Vec3::UnitZ()};
  const double distance = std::hypot(z.x, z.y);
  if (distance > 1e-9 * blockSize)
    z.toolVector = Vec3(-std::sin(tilt) * z.x / distance, -std::sin(tilt) * z.y / distance, std::cos(tilt));
  return z;
}

CubicZone moved(CubicZone z, double cx, double cy) {
  z.x += cx;
  z.y += cy;
  return z;
}

}  // namespace

std::vector<CubicZone> cubicZoneGrid(int n, double blockSize, double tilt, double cx, double cy) {
  std::vector<CubicZone> zones;
  if (n == 3) {
    for (const auto& s : kSeedZones) zones.push_back(moved(gridZone(s.column, s.row, n, blockSize, tilt, s.name), cx, cy));
    return zones;
  }
  for (int row = 0; row < n; ++row)
    for (int column = 0; column < n; ++column)
      zones.push_back(moved(gridZone(column, row, n, blockSize, tilt, fmt::format("r{}c{}", row + 1, column + 1)), cx, cy));
  return zones;
}

CubicTestSpec seed001CubicTest() {
  CubicTestSpec spec;
  spec.zones = cubicZoneGrid(3, spec.blockSize, 30 * kDeg);
  return spec;
}

std::optional<SpecProblem> cubicTestSpecProblem(const CubicTestSpec& s) {
  const auto problem = [](std::string key, std::string what) { return SpecProblem{std::move(key), std::move(what)}; };
  if (!(s.blockSize > 0 && s.blockSize <= 10000)) return problem("block", "must be in (0, 10000] mm");
  if (!(s.zoneSize > 0 && s.zoneSize <= s.blockSize)) return problem("zone_size", "must be positive and at most the block size");
  if (!(s.tool.radius >= 1e-3 && s.tool.radius <= 1000)) return problem("tool.radius", "must be in [0.001, 1000] mm");
  if (!(s.pick >= 1e-4 && s.pick <= s.zoneSize)) return problem("pick", "must be in [0.0001 mm, the zone size]");
  if (static_cast<double>(s.zones.size()) * (s.zoneSize / s.pick) > 1e7) return problem("pick", "gives more than 10 million passes");
  if (!(s.depth >= 0 && s.depth <= s.tool.radius)) return problem("depth", "must be in [0, the tool radius]");
  if (!(s.feed > 0 && s.feed <= 1e6)) return problem("feed", "must be in (0, 1e6] mm/min");
  if (!(std::abs(s.topHeight) <= 1e4)) return problem("top", "must be within +-10000 mm");
  if (!(std::abs(s.centreX) <= 1e4 && std::abs(s.centreY) <= 1e4)) return problem("centre", "must be within +-10000 mm");
  if (s.zones.empty()) return problem("zones", "no zone to machine");
  for (size_t k = 0; k < s.zones.size(); ++k) {
    const auto& z = s.zones[k];
    const std::string at = fmt::format("zones[{}]", k);
    if (!(std::abs(z.x - s.centreX) + s.zoneSize / 2 <= s.blockSize / 2 * (1 + 1e-12) &&
          std::abs(z.y - s.centreY) + s.zoneSize / 2 <= s.blockSize / 2 * (1 + 1e-12)))
      return problem(at, fmt::format("zone {} at ({:g}, {:g}) mm lies partly outside the block", z.name, z.x, z.y));
    if (!(std::abs(z.toolVector.norm() - 1) < 1e-9 && z.toolVector.z() >= 0.1))
      return problem(at, fmt::format("zone {}: the tool vector must be a unit vector tilted less than 84 deg from the face normal",
                                     z.name));
  }
  return std::nullopt;
}

Vec3 toolTipForContact(const Vec3& contact, const Vec3& v, const CuttingTool& tool) {
  if (tool.shape == ToolShape::Ball) return contact + tool.radius * Vec3(-v.x(), -v.y(), 1 - v.z());
  // The disc's lowest rim point lies along the downward slope of its plane.
  const Vec3 down = v.z() * v - Vec3::UnitZ();
  const double n = down.norm();
  return n < 1e-12 ? contact : Vec3(contact - tool.radius * down / n);
}

std::vector<CubicZonePath> cubicToolPath(const KinematicModel& nominal, const CubicTestSpec& spec) {
  const auto passes = static_cast<int>(std::ceil(spec.zoneSize / spec.pick - 1e-9)) + 1;
  const double pitch = spec.zoneSize / (passes - 1), half = spec.zoneSize / 2;
  const int axes = nominal.jointCount;
  std::vector<CubicZonePath> out;
  for (const auto& zone : spec.zones) {
    CubicZonePath path;
    path.tips.resize(2 * passes, 3);
    path.q.resize(2 * passes, axes);
    IkOptions options;
    options.branch = spec.branch;
    for (int k = 0; k < passes; ++k) {
      const double y = zone.y - half + k * pitch;
      const double from = k % 2 == 0 ? zone.x - half : zone.x + half;
      const double to = k % 2 == 0 ? zone.x + half : zone.x - half;
      for (int e = 0; e < 2; ++e) {
        const int row = 2 * k + e;
        const Vec3 tip = toolTipForContact(Vec3(e == 0 ? from : to, y, spec.topHeight), zone.toolVector, spec.tool);
        path.tips.row(row) = tip.transpose();
        IkSolution s;
        try {
          s = solveIk(nominal, tip, zone.toolVector, options);
        } catch (const UnreachablePose& e) {
          throw UnreachableTarget(static_cast<size_t>(row), "zone " + zone.name + ": " + e.what());
        }
        if (row == 0) {
          path.clamped = s.q;
          options.hint = s.q;
        }
        for (int a = 0; a < axes; ++a) path.q(row, a) = s.q[static_cast<size_t>(a)];
      }
    }
    const auto clear = [&](Eigen::Index row) {
      const Vec3 tip = path.tips.row(row).transpose();
      return solveIk(nominal, tip + (spec.depth + kCubicClearance) * zone.toolVector, zone.toolVector, options).q;
    };
    try {
      path.approach = clear(0);
      path.retract = clear(path.tips.rows() - 1);
    } catch (const UnreachablePose& e) {
      throw UnreachableTarget(0, "zone " + zone.name + ", clear of the stock: " + e.what());
    }
    path.direction = motionDirections(path.q);
    out.push_back(std::move(path));
  }
  return out;
}

DirectionMatrix motionDirections(const JointMatrix& q) {
  DirectionMatrix direction(q.rows(), q.cols());
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::Index from = i == 0 ? 0 : i - 1, to = i == 0 ? std::min<Eigen::Index>(1, q.rows() - 1) : i;
    for (Eigen::Index a = 0; a < q.cols(); ++a) {
      const double d = q(to, a) - q(from, a);
      direction(i, a) = std::abs(d) < 1e-12 ? 0 : (d > 0 ? 1 : -1);
    }
  }
  return direction;
}

std::vector<CubicZonePath> recordedCuttingRuns(const Machine& machine, const JointMatrix& q, double still) {
  std::vector<CubicZonePath> runs;
  const auto clampedFrom = [&](Eigen::Index first, Eigen::Index i) {
    for (int a = 0; a < machine.commandedCount(); ++a)
      if (machine.axes[static_cast<size_t>(a)].isRotary() && std::abs(q(i, a) - q(first, a)) > still) return false;
    return true;
  };
  for (Eigen::Index first = 0; first < q.rows();) {
    Eigen::Index end = first + 1;
    while (end < q.rows() && clampedFrom(first, end)) ++end;
    if (end - first >= 2) {
      CubicZonePath run;
      run.q = q.middleRows(first, end - first);
      run.clamped.assign(run.q.row(0).data(), run.q.row(0).data() + run.q.cols());
      run.direction = motionDirections(run.q);
      runs.push_back(std::move(run));
    }
    first = end;
  }
  return runs;
}

std::vector<std::array<double, 2>> cubicZoneRunPoints(const CubicTestSpec& spec, bool slopes) {
  const double a = spec.zoneSize / 4;
  if (slopes) return {{0, 0}, {a, 0}, {0, a}};
  return {{0, 0}};
}

std::vector<MeasurementRun> cubicZoneRuns(const KinematicModel& nominal, const CubicTestSpec& spec, bool slopes) {
  const auto points = cubicZoneRunPoints(spec, slopes);
  std::vector<MeasurementRun> runs;
  IkOptions options;
  options.branch = spec.branch;
  for (const auto& zone : spec.zones) {
    MeasurementRun run;
    run.name = "zone-" + zone.name;
    run.instrument = Instrument::Directional;
    run.setup.direction = Vec3::UnitZ();
    run.q.resize(static_cast<Eigen::Index>(points.size()), nominal.jointCount);
    for (size_t k = 0; k < points.size(); ++k) {
      const Vec3 contact(zone.x + points[k][0], zone.y + points[k][1], spec.topHeight);
      const Vec3 tip = toolTipForContact(contact, zone.toolVector, spec.tool);
      IkSolution s;
      try {
        s = solveIk(nominal, tip, zone.toolVector, options);
      } catch (const UnreachablePose& e) {
        throw UnreachableTarget(k, "zone " + zone.name + ": " + e.what());
      }
      options.hint = s.q;
      for (int a = 0; a < nominal.jointCount; ++a) run.q(static_cast<Eigen::Index>(k), a) = s.q[static_cast<size_t>(a)];
      if (k == 0) {
        // The surface point the zone's height is read at: the ball centre, or the flat end's
        // contact point, in the tool frame.
        const Vec3 reference = spec.tool.shape == ToolShape::Ball ? Vec3(contact + spec.tool.radius * Vec3::UnitZ()) : contact;
        const Pose tool = toolInWorkpiece(nominal, s.q.data());
        run.setup.toolBall = tool.linear().transpose() * (reference - tip);
      }
    }
    options.hint.reset();
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace mtacc
