#include "mtacc/io/cubic_program.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

// Axis words of one pose; continuous rotary axes in [0, 360) deg, as a rollover axis shows them.
std::string axisWords(const Machine& m, const double* q, bool linear, bool rotary) {
  std::string words;
  for (int k = 0; k < m.commandedCount(); ++k) {
    const Axis& a = m.axes[static_cast<size_t>(k)];
    if (a.isRotary() ? !rotary : !linear) continue;
    double v = q[k];
    if (a.isRotary()) {
      v /= kDeg;
      if (!a.travel) v = std::fmod(std::fmod(v, 360.0) + 360.0, 360.0);
      if (std::abs(v) < 5e-5 || std::abs(v - 360.0) < 5e-5) v = 0.0;
    }
    words += fmt::format(" {}{:.4f}", a.name, v);
  }
  return words;
}

}  // namespace

std::string cubicNcProgram(const Machine& m, const CubicTestSpec& spec, const std::vector<CubicZonePath>& path) {
  std::string g = fmt::format("; mtacc cubic machining test (seed 001): {:g} mm block, {} zones of {:g} mm, {} end mill R{:g} mm\n",
                              spec.blockSize, spec.zones.size(), spec.zoneSize,
                              spec.tool.shape == ToolShape::Ball ? "ball" : "flat", spec.tool.radius);
  g += fmt::format("; machine {}; pick {:g} mm, depth {:g} mm; axis positions in mm and deg; feed {:g} mm/min\n", m.name,
                   spec.pick, spec.depth, spec.feed);
  g += "; each zone: position the rotary axes with the tool clear of the part, clamp them, cut 3-axis zig-zag passes\nG90 G94\n";
  int n = 0;
  const auto line = [&](const std::string& body) { g += fmt::format("N{} {}\n", 10 * ++n, body); };
  for (size_t z = 0; z < path.size(); ++z) {
    const auto& zone = spec.zones[z];
    const auto& p = path[z];
    const Vec3& t = zone.toolVector;
    g += fmt::format("; zone {}: tool vector ({:.6f}, {:.6f}, {:.6f})\n", zone.name, t.x(), t.y(), t.z());
    line("G00" + axisWords(m, p.approach.data(), true, true));
    g += "; clamp the rotary axes\n";
    for (Eigen::Index i = 0; i < p.q.rows(); ++i)
      line("G01" + axisWords(m, p.q.row(i).data(), true, false) + (i == 0 ? fmt::format(" F{:g}", spec.feed) : ""));
    line("G00" + axisWords(m, p.retract.data(), true, false));
    g += "; unclamp the rotary axes\n";
  }
  return g + "M30\n";
}

std::string cubicClData(const CubicTestSpec& spec, const std::vector<CubicZonePath>& path) {
  std::string cl = "zone,x,y,z,i,j,k\n";
  for (size_t z = 0; z < path.size(); ++z) {
    const Vec3& v = spec.zones[z].toolVector;
    for (Eigen::Index i = 0; i < path[z].tips.rows(); ++i)
      cl += fmt::format("{},{},{},{},{},{},{}\n", spec.zones[z].name, path[z].tips(i, 0), path[z].tips(i, 1), path[z].tips(i, 2),
                        v.x(), v.y(), v.z());
  }
  return cl;
}

}  // namespace mtacc
