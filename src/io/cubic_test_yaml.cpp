#include "mtacc/io/cubic_test_yaml.hpp"

#include "mtacc/io/bundled_data.hpp"
#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

using yamlin::Context;

// Zones in the workpiece frame; a list gives them relative to the block centre (cx, cy).
std::vector<CubicZone> zonesOf(const Context& ctx, const YAML::Node& node, double block, double cx, double cy) {
  if (yamlin::isMap(node)) {
    yamlin::rejectUnknownKeys(ctx, node, "zones", {"grid", "tilt"});
    const int n = yamlin::wholeNumber(ctx, node["grid"], "zones.grid", 1, 15);
    const double tilt = yamlin::quantity(ctx, node["tilt"], "zones.tilt", Dimension::Angle);
    if (!(std::abs(tilt) <= 84 * kDeg)) ctx.fail(node["tilt"], "zones.tilt", "must be within +-84 deg");
    return cubicZoneGrid(n, block, tilt, cx, cy);
  }
  if (!yamlin::isSequence(node) || node.size() == 0)
    ctx.fail(node, "zones", "expected {grid: N, tilt: ANGLE} or a list of {name, centre: [x mm, y mm], tool: [i, j, k]}");
  if (node.size() > 225) ctx.fail(node, "zones", "at most 225 zones");
  std::vector<CubicZone> zones;
  for (size_t k = 0; k < node.size(); ++k) {
    const auto z = node[k];
    const std::string key = "zones[" + std::to_string(k) + "]";
    if (!yamlin::isMap(z)) ctx.fail(z, key, "expected {name, centre: [x mm, y mm], tool: [i, j, k]}");
    yamlin::rejectUnknownKeys(ctx, z, key, {"name", "centre", "tool"});
    CubicZone zone;
    zone.name = z["name"] ? yamlin::scalar(ctx, z["name"], key + ".name") : "zone " + std::to_string(k + 1);
    const auto c = z["centre"];
    if (!yamlin::isSequence(c) || c.size() != 2) ctx.fail(c ? c : z, key + ".centre", "expected [x mm, y mm]");
    zone.x = cx + yamlin::quantity(ctx, c[0], key + ".centre", Dimension::Length);
    zone.y = cy + yamlin::quantity(ctx, c[1], key + ".centre", Dimension::Length);
    zone.toolVector = z["tool"] ? yamlin::unitVector(ctx, z["tool"], key + ".tool") : Vec3::UnitZ();
    zones.push_back(zone);
  }
  return zones;
}

}  // namespace

CubicTestSpec parseCubicTest(const std::string& text, const std::string& source) {
  const Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!root.IsMap()) ctx.fail(root, "", "expected a mapping with block, zones and tool");
  yamlin::rejectUnknownKeys(ctx, root, "",
                            {"name", "description", "block", "centre", "zone_size", "top", "zones", "tool", "pick", "depth", "feed", "branch"});
  CubicTestSpec s;
  const auto length = [&](const char* key, double& into) {
    if (root[key]) into = yamlin::quantity(ctx, root[key], key, Dimension::Length);
  };
  length("block", s.blockSize);
  if (!(s.blockSize > 0 && s.blockSize <= 10000)) ctx.fail(root["block"], "block", "must be in (0, 10000] mm");
  const auto zones = root["zones"];
  const bool grid = yamlin::isMap(zones) && zones["grid"];
  s.zoneSize = s.blockSize / (grid ? yamlin::wholeNumber(ctx, zones["grid"], "zones.grid", 1, 15) : 3);
  length("zone_size", s.zoneSize);
  length("top", s.topHeight);
  if (const auto c = root["centre"]) {
    if (!yamlin::isSequence(c) || c.size() != 2) ctx.fail(c, "centre", "expected [x mm, y mm]");
    s.centreX = yamlin::quantity(ctx, c[0], "centre", Dimension::Length);
    s.centreY = yamlin::quantity(ctx, c[1], "centre", Dimension::Length);
  }
  length("pick", s.pick);
  length("depth", s.depth);
  if (root["feed"]) s.feed = yamlin::number(ctx, root["feed"], "feed");
  s.zones = zones ? zonesOf(ctx, zones, s.blockSize, s.centreX, s.centreY)
                  : cubicZoneGrid(3, s.blockSize, 30 * kDeg, s.centreX, s.centreY);
  if (const auto t = root["tool"]) {
    if (!yamlin::isMap(t)) ctx.fail(t, "tool", "expected {shape: ball | flat, radius: LENGTH}");
    yamlin::rejectUnknownKeys(ctx, t, "tool", {"shape", "radius"});
    if (t["shape"]) {
      const auto shape = yamlin::scalar(ctx, t["shape"], "tool.shape");
      if (shape != "ball" && shape != "flat") ctx.fail(t["shape"], "tool.shape", "expected ball or flat");
      s.tool.shape = shape == "ball" ? ToolShape::Ball : ToolShape::Flat;
    }
    if (t["radius"]) s.tool.radius = yamlin::quantity(ctx, t["radius"], "tool.radius", Dimension::Length);
  }
  if (root["branch"]) {
    const auto b = yamlin::scalar(ctx, root["branch"], "branch");
    if (b != "positive" && b != "negative" && b != "auto") ctx.fail(root["branch"], "branch", "expected positive, negative or auto");
    s.branch = parseTiltBranch(b);
  }
  if (const auto problem = cubicTestSpecProblem(s)) {
    const auto bracket = problem->key.find('[');
    YAML::Node node = root[problem->key.substr(0, problem->key.find_first_of(".["))];
    if (bracket != std::string::npos && yamlin::isSequence(node))
      node = node[std::stoul(problem->key.substr(bracket + 1))];
    ctx.fail(node ? node : root, problem->key, problem->what);
  }
  return s;
}

CubicTestSpec loadCubicTest(const std::string& pathOrName) {
  const std::string path = resolveBundled("test-pieces", pathOrName);
  return parseCubicTest(readTextFile(path), path);
}

}  // namespace mtacc
