#include "mtacc/io/plan_yaml.hpp"

#include <map>

#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/measurement/standard_paths.hpp"
#include "mtacc/procedures/cone_ballbar.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

using yamlin::Context;

std::vector<double> poseOf(const Context& ctx, const Machine& m, const YAML::Node& node, const std::string& key) {
  std::vector<double> q(static_cast<size_t>(m.commandedCount()), 0.0);
  if (!node) return q;
  if (!node.IsMap()) ctx.fail(node, key, "expected a mapping of axis names to positions, e.g. {B: -30 deg}");
  for (const auto& kv : node) {
    const auto axis = kv.first.as<std::string>();
    const int j = m.commandedAxisIndex(axis);
    if (j < 0) ctx.fail(kv.first, key + "." + axis, "no commanded axis '" + axis + "' on " + m.name);
    q[static_cast<size_t>(j)] = yamlin::quantity(ctx, kv.second, key + "." + axis,
                                                 m.axes[static_cast<size_t>(j)].isRotary() ? Dimension::Angle : Dimension::Length);
  }
  return q;
}

int count(const Context& ctx, const YAML::Node& node, const std::string& key, int fallback, int minimum) {
  return node ? yamlin::wholeNumber(ctx, node, key, minimum, kMaxPointsPerRun) : fallback;
}

double feedOf(const Context& ctx, const YAML::Node& node, const std::string& key) {
  if (!node) return 1000.0;
  std::string text = yamlin::scalar(ctx, node, key);
  const auto slash = text.rfind("/min");
  if (slash == std::string::npos || slash + 4 != text.size()) ctx.fail(node, key, "expected a feed in mm/min");
  std::string reason;
  const auto q = parseQuantity(text.substr(0, slash), &reason);
  if (!q || q->dimension != Dimension::Length || !(q->value > 0)) ctx.fail(node, key, "expected a positive feed in mm/min");
  return q->value;
}

std::vector<MeasurementRun> generate(const Context& ctx, const KinematicModel& nominal, const YAML::Node& entry,
                                     const std::string& key) {
  const Machine& m = *nominal.machine;
  const Vec3 toolBall = entry["tool_ball"] ? yamlin::lengthVector(ctx, entry["tool_ball"], key + ".tool_ball") : Vec3::Zero();
  auto wrap = [&](auto&& make) -> std::vector<MeasurementRun> {
    try {
      auto runs = make();
      for (const auto& run : runs)
        if (const auto violation = travelViolation(m, run); !violation.empty())
          ctx.fail(entry, key, "the run leaves the machine's travel at " + violation);
      return runs;
    } catch (const InvalidInput& e) {
      ctx.fail(entry, key, e.what());
    } catch (const UnreachablePose& e) {
      ctx.fail(entry, key, std::string("unreachable pose: ") + e.what());
    }
  };
  if (const auto c = entry["circle"]) {
    const std::string k = key + ".circle";
    yamlin::rejectUnknownKeys(ctx, c, k, {"plane", "centre", "radius", "points", "feed", "both_directions", "pose"});
    BallbarCircleSpec s;
    s.plane = c["plane"] ? yamlin::scalar(ctx, c["plane"], k + ".plane") : "XY";
    if (c["centre"]) s.centre = yamlin::lengthVector(ctx, c["centre"], k + ".centre");
    if (c["radius"]) s.radius = yamlin::size(ctx, c["radius"], k + ".radius", Dimension::Length);
    s.points = count(ctx, c["points"], k + ".points", 360, 8);
    s.feed = feedOf(ctx, c["feed"], k + ".feed");
    if (c["both_directions"]) s.bothDirections = yamlin::boolean(ctx, c["both_directions"], k + ".both_directions");
    s.pose = poseOf(ctx, m, c["pose"], k + ".pose");
    s.toolBall = toolBall;
    return wrap([&] { return std::vector{ballbarCircle(nominal, s)}; });
  }
  if (const auto r = entry["rotary"]) {
    const std::string k = key + ".rotary";
    yamlin::rejectUnknownKeys(ctx, r, k, {"axis", "mode", "length", "work_ball", "from", "to", "points", "feed", "pose"});
    BallbarRotarySpec s;
    s.axis = yamlin::scalar(ctx, r["axis"], k + ".axis");
    s.length = yamlin::size(ctx, r["length"], k + ".length", Dimension::Length);
    s.workBall = yamlin::lengthVector(ctx, r["work_ball"], k + ".work_ball");
    if (r["from"]) s.from = yamlin::quantity(ctx, r["from"], k + ".from", Dimension::Angle);
    if (r["to"]) s.to = yamlin::quantity(ctx, r["to"], k + ".to", Dimension::Angle);
    s.points = count(ctx, r["points"], k + ".points", 360, 8);
    s.feed = feedOf(ctx, r["feed"], k + ".feed");
    s.pose = poseOf(ctx, m, r["pose"], k + ".pose");
    s.toolBall = toolBall;
    return wrap([&] {
      s.mode = parseRotaryTestMode(r["mode"] ? yamlin::scalar(ctx, r["mode"], k + ".mode") : "radial");
      return std::vector{ballbarRotaryTest(nominal, s)};
    });
  }
  if (const auto sp = entry["sphere"]) {
    const std::string k = key + ".sphere";
    yamlin::rejectUnknownKeys(ctx, sp, k, {"instrument", "axis", "from", "to", "points", "angles", "spheres", "pose"});
    SphereTestSpec s;
    const auto instrument = parseInstrument(sp["instrument"] ? yamlin::scalar(ctx, sp["instrument"], k + ".instrument") : "rtest");
    if (!instrument || (*instrument != Instrument::RTest && *instrument != Instrument::TouchProbe))
      ctx.fail(sp["instrument"], k + ".instrument", "expected rtest or probe");
    s.instrument = *instrument;
    s.axis = yamlin::scalar(ctx, sp["axis"], k + ".axis");
    if (const auto angles = sp["angles"]) {  // the positions one by one (a designed plan's), in place of from, to, points
      for (const char* range : {"from", "to", "points"})
        if (sp[range]) ctx.fail(sp[range], k + "." + range, "give either angles or from, to and points");
      if (!angles.IsSequence() || angles.size() == 0 || angles.size() > static_cast<size_t>(kMaxPointsPerRun))
        ctx.fail(angles, k + ".angles", "expected a list of angles [0 deg, 30 deg, ...]");
      for (size_t i = 0; i < angles.size(); ++i)
        s.angles.push_back(yamlin::quantity(ctx, angles[i], k + ".angles[" + std::to_string(i) + "]", Dimension::Angle));
    } else {
      const double from = yamlin::quantity(ctx, sp["from"], k + ".from", Dimension::Angle);
      const double to = yamlin::quantity(ctx, sp["to"], k + ".to", Dimension::Angle);
      const int n = count(ctx, sp["points"], k + ".points", 12, 1);
      for (int i = 0; i < n; ++i) s.angles.push_back(n == 1 ? from : from + (to - from) * i / (n - 1));
    }
    if (!sp["spheres"] || !sp["spheres"].IsSequence()) ctx.fail(sp, k + ".spheres", "expected a list of positions [x mm, y mm, z mm]");
    for (size_t i = 0; i < sp["spheres"].size(); ++i)
      s.spheres.push_back(yamlin::lengthVector(ctx, sp["spheres"][i], k + ".spheres[" + std::to_string(i) + "]"));
    s.pose = poseOf(ctx, m, sp["pose"], k + ".pose");
    s.toolBall = toolBall;
    return wrap([&] { return sphereTest(nominal, s); });
  }
  if (const auto c = entry["cone"]) {
    const std::string k = key + ".cone";
    yamlin::rejectUnknownKeys(ctx, c, k, {"preset", "points", "branch", "feed"});
    const auto preset = conePreset(yamlin::scalar(ctx, c["preset"], k + ".preset"));
    if (!preset) ctx.fail(c["preset"], k + ".preset", "unknown preset (" + conePresetNames() + ")");
    const int n = count(ctx, c["points"], k + ".points", 360, 8);
    const double feed = feedOf(ctx, c["feed"], k + ".feed");
    return wrap([&] {
      const auto branch = parseTiltBranch(c["branch"] ? yamlin::scalar(ctx, c["branch"], k + ".branch") : "negative");
      return std::vector{ballbarCone(nominal, *preset, n, {branch, feed})};
    });
  }
  if (const auto z = entry["cubic_zones"]) {
    const std::string k = key + ".cubic_zones";
    if (!yamlin::isMap(z)) ctx.fail(z, k, "expected {test: FILE or bundled name, slopes: true | false}");
    yamlin::rejectUnknownKeys(ctx, z, k, {"test", "slopes"});
    const auto spec = loadCubicTest(z["test"] ? yamlin::scalar(ctx, z["test"], k + ".test") : "seed001-cubic");
    const bool slopes = z["slopes"] ? yamlin::boolean(ctx, z["slopes"], k + ".slopes") : false;
    return wrap([&] { return cubicZoneRuns(nominal, spec, slopes); });
  }
  ctx.fail(entry, key, "expected one of circle, rotary, sphere, cone, cubic_zones");
}

}  // namespace

TestPlan parseTestPlan(const KinematicModel& nominal, const std::string& text, const std::string& source) {
  const Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!root.IsMap()) ctx.fail(root, "", "expected a mapping with 'runs'");
  yamlin::rejectUnknownKeys(ctx, root, "", {"name", "description", "runs", "parameters"});
  TestPlan plan;
  plan.name = root["name"] ? yamlin::scalar(ctx, root["name"], "name") : source;
  const auto runs = root["runs"];
  if (!runs || !runs.IsSequence() || runs.size() == 0) ctx.fail(runs ? runs : root, "runs", "expected a list of runs");
  std::map<std::string, int> runLines;  // name -> line of its entry
  for (size_t i = 0; i < runs.size(); ++i) {
    const std::string key = "runs[" + std::to_string(i) + "]";
    const auto entry = runs[i];
    if (!entry.IsMap()) ctx.fail(entry, key, "expected a mapping");
    yamlin::rejectUnknownKeys(ctx, entry, key, {"name", "estimate", "noise", "tool_ball", "circle", "rotary", "sphere", "cone", "cubic_zones"});
    auto generated = generate(ctx, nominal, entry, key);
    for (size_t g = 0; g < generated.size(); ++g) {
      auto& run = generated[g];
      if (entry["name"])
        run.name = yamlin::scalar(ctx, entry["name"], key + ".name") + (generated.size() > 1 ? "-" + std::to_string(g + 1) : "");
      if (const auto e = entry["estimate"]) {
        if (!yamlin::isSequence(e)) ctx.fail(e, key + ".estimate", "expected a list such as [xW, yW, zW]");
        for (const auto& item : e) {
          const auto name = yamlin::scalar(ctx, item, key + ".estimate");
          const auto p = parseSetupParameter(name);
          if (!p || !appliesTo(*p, run.instrument))
            ctx.fail(item, key + ".estimate", "'" + name + "' is not a set-up parameter of a " + instrumentName(run.instrument));
          run.estimate.push_back(*p);
        }
      }
      if (const auto n = entry["noise"]) {  // the readings' expected standard deviation, for observability's prediction
        run.noise = yamlin::size(ctx, n, key + ".noise", Dimension::Length);
        if (*run.noise > 1.0) ctx.fail(n, key + ".noise", "must be from 1 nm to 1 mm");
      }
      if (const auto [it, added] = runLines.emplace(run.name, entry.Mark().line + 1); !added)
        ctx.fail(entry["name"] ? entry["name"] : entry, key + ".name",
                 "a run named '" + run.name + "' is already on line " + std::to_string(it->second) + " (each run writes its own file)");
      plan.runs.push_back(std::move(run));
    }
  }
  if (const auto p = root["parameters"]) {
    if (!yamlin::isSequence(p)) ctx.fail(p, "parameters", "expected a list of error names");
    for (const auto& item : p) plan.parameters.push_back(yamlin::scalar(ctx, item, "parameters"));
    plan.parametersAt = ctx.at(p, "parameters");
  }
  return plan;
}

TestPlan loadTestPlan(const KinematicModel& nominal, const std::string& pathOrName) {
  const std::string path = resolveBundled("plans", pathOrName);
  return parseTestPlan(nominal, readTextFile(path), path);
}

}  // namespace mtacc
