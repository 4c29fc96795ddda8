#include "mtacc/io/seed002_eccentricities_yaml.hpp"

#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {

Seed002Measurements parseSeed002Eccentricities(const std::string& yamlText, const std::string& sourceName) {
  const yamlin::Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  if (!root.IsMap()) ctx.fail(root, "", "expected a mapping with 'setup' and 'eccentricities'");
  yamlin::rejectUnknownKeys(ctx, root, "", {"setup", "eccentricities", "description", "source"});
  Seed002Measurements m;
  m.file = sourceName;
  const auto setup = root["setup"];
  if (!yamlin::isMap(setup)) ctx.fail(root, "setup", "expected a mapping {R_B, R_B2, R_C, Z_C, Z_C2} of lengths");
  yamlin::rejectUnknownKeys(ctx, setup, "setup", {"R_B", "R_B2", "R_C", "Z_C", "Z_C2"});
  auto length = [&](const char* key) { return yamlin::size(ctx, setup[key], std::string("setup.") + key, Dimension::Length); };
  m.setup = {length("R_B"), length("R_B2"), length("R_C"), length("Z_C"), length("Z_C2")};
  m.setupLine = setup.Mark().line + 1;
  const auto runs = root["eccentricities"];
  if (!yamlin::isMap(runs)) ctx.fail(root, "eccentricities", "expected a mapping of the six runs");
  yamlin::rejectUnknownKeys(ctx, runs, "eccentricities", {"B_X", "B_Y", "C_axial", "C_radial", "C_radial_Z_C2", "C_radial_Z_C2_R_B2"});
  // Each run's two components in its plot plane: x and z for the B runs, x and y for the C runs.
  auto read = [&](const char* run, const char* second, double& first, double& other) {
    const std::string key = std::string("eccentricities.") + run;
    const auto node = runs[run];
    if (!yamlin::isMap(node)) ctx.fail(runs, key, std::string("expected {ex, ") + second + "} of the run");
    yamlin::rejectUnknownKeys(ctx, node, key, {"ex", second});
    first = yamlin::quantity(ctx, node["ex"], key + ".ex", Dimension::Length);
    other = yamlin::quantity(ctx, node[second], key + "." + second, Dimension::Length);
  };
  auto& e = m.eccentricities;
  read("B_X", "ez", e.bxEx, e.bxEz);
  read("B_Y", "ez", e.byEx, e.byEz);
  read("C_axial", "ey", e.caEx, e.caEy);
  read("C_radial", "ey", e.crEx, e.crEy);
  read("C_radial_Z_C2", "ey", e.cr1Ex, e.cr1Ey);
  read("C_radial_Z_C2_R_B2", "ey", e.cr2Ex, e.cr2Ey);
  return m;
}

Seed002Measurements loadSeed002Eccentricities(const std::string& path) { return parseSeed002Eccentricities(readTextFile(path), path); }

}  // namespace mtacc
