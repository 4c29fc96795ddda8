#include "mtacc/io/acceptance_yaml.hpp"

#include <filesystem>
#include <set>

#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "yaml_input.hpp"

namespace mtacc {

AcceptancePlan loadAcceptancePlan(const std::string& path) { return parseAcceptancePlan(readTextFile(path), path); }

AcceptancePlan parseAcceptancePlan(const std::string& yamlText, const std::string& sourceName) {
  const yamlin::Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping with title, tolerances, decision_rule and tests (docs/file-formats.md)");
  yamlin::rejectUnknownKeys(ctx, root, "", {"title", "tolerances", "decision_rule", "tests"});
  const auto folder = std::filesystem::path(sourceName).parent_path();
  const auto resolve = [&](const YAML::Node& node, const std::string& key) {
    const auto p = std::filesystem::path(yamlin::scalar(ctx, node, key));
    return (p.is_absolute() ? p : folder / p).lexically_normal().string();
  };
  AcceptancePlan plan;
  plan.file = sourceName;
  plan.title = root["title"] ? yamlin::scalar(ctx, root["title"], "title") : "Acceptance tests";
  if (root["tolerances"]) plan.tolerances = resolve(root["tolerances"], "tolerances");
  if (root["decision_rule"]) {
    const auto rule = yamlin::scalar(ctx, root["decision_rule"], "decision_rule");
    if (rule == "iso14253-1") plan.decisionRule = DecisionRule::Iso14253_1;
    else if (rule == "simple") plan.decisionRule = DecisionRule::Simple;
    else ctx.fail(root["decision_rule"], "decision_rule", "expected iso14253-1 or simple");
  }
  const auto tests = root["tests"];
  if (!yamlin::isSequence(tests) || tests.size() == 0) ctx.fail(tests, "tests", "expected a list of tests");
  std::set<std::string> names;
  for (size_t i = 0; i < tests.size(); ++i) {
    const auto t = tests[i];
    const std::string key = "tests[" + std::to_string(i) + "]";
    if (!yamlin::isMap(t)) ctx.fail(t, key, "expected a test: {test: positioning | rotary | geometric | circular | drift, data: FILE, ...}");
    yamlin::rejectUnknownKeys(ctx, t, key, {"name", "test", "data", "conditions", "tolerances", "calibration", "drift"});
    AcceptanceTestSpec s;
    s.line = ctx.at(t, key).line;
    s.key = key;
    if (!t["test"]) ctx.fail(t, key + ".test", "missing: positioning, rotary, geometric, circular or drift");
    const auto type = yamlin::scalar(ctx, t["test"], key + ".test");
    if (type == "positioning") s.type = AcceptanceTestType::Positioning;
    else if (type == "rotary") s.type = AcceptanceTestType::Rotary;
    else if (type == "geometric") s.type = AcceptanceTestType::Geometric;
    else if (type == "circular") s.type = AcceptanceTestType::Circular;
    else if (type == "drift") s.type = AcceptanceTestType::Drift;
    else ctx.fail(t["test"], key + ".test",
                  "expected positioning (ISO 230-2), rotary (ISO 10791-6), geometric (ISO 230-1), circular (ISO 230-4) or drift (ISO 230-3)");
    if (!t["data"]) ctx.fail(t, key + ".data", "missing: the test's data file");
    s.data = resolve(t["data"], key + ".data");
    s.name = t["name"] ? yamlin::scalar(ctx, t["name"], key + ".name") : std::filesystem::path(s.data).stem().string();
    if (!names.insert(s.name).second) ctx.fail(t["name"] ? t["name"] : t["data"], key + ".name", "a second test named '" + s.name + "'");
    if (t["tolerances"]) s.tolerances = resolve(t["tolerances"], key + ".tolerances");
    if (s.type == AcceptanceTestType::Positioning) {
      for (const char* k : {"calibration", "drift"})
        if (t[k]) ctx.fail(t[k], key + "." + k, "a positioning test states its instrument in its conditions file");
      if (t["conditions"]) s.conditions = resolve(t["conditions"], key + ".conditions");
    } else {
      if (t["conditions"]) ctx.fail(t["conditions"], key + ".conditions", "a conditions file is for a positioning test; give calibration and drift");
      if (s.type == AcceptanceTestType::Drift && t["drift"]) ctx.fail(t["drift"], key + ".drift", "a drift test measures the drift: it has no E_VE");
      // A geometric test of an angular component states both in angles: its unit is known only
      // from the data, so either dimension is read here and checked against it when it is run.
      for (const char* k : {"calibration", "drift"}) {
        if (!t[k]) continue;
        const Quantity q = yamlin::anyQuantity(ctx, t[k], key + "." + k);
        if (!(q.value >= 0) || (q.dimension == Dimension::Length ? q.value > 1.0 : q.value > kDeg))
          ctx.fail(t[k], key + "." + k, "expected 0 to 1 mm (or 1 deg)");
        if (s.type != AcceptanceTestType::Geometric && q.dimension != Dimension::Length) ctx.fail(t[k], key + "." + k, "expected a length");
        (std::string(k) == "calibration" ? s.calibration : s.drift) = q;
      }
    }
    plan.tests.push_back(std::move(s));
  }
  return plan;
}

}  // namespace mtacc
