#include "mtacc/workflows/multitasking_identification.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/aliases.hpp"

namespace mtacc {
namespace {

// Seed 002's names (Table 1) with their values, lengths first.
std::array<std::pair<const char*, double>, 12> named(const Seed002Deviations& d) {
  return {{{"dxBT", d.dxBT}, {"dzBT", d.dzBT}, {"dxCZ", d.dxCZ}, {"dyCZ", d.dyCZ}, {"alphaBT", d.alphaBT}, {"alphaXB", d.alphaXB},
           {"betaXB", d.betaXB}, {"gammaXB", d.gammaXB}, {"alphaYZ", d.alphaYZ}, {"betaYZ", d.betaYZ}, {"alphaCZ", d.alphaCZ},
           {"betaCZ", d.betaCZ}}};
}

bool isLength(const char* name) { return name[0] == 'd'; }

}  // namespace

const OptionSchema& multitaskingSchema() {
  static const OptionSchema schema{
      "multitasking",
      {{.key = "data", .kind = OptionKind::Text,
        .help = "eccentricities of the six ball-bar runs and their set-up (YAML, docs/file-formats.md)", .positional = true}}};
  return schema;
}

MultitaskingIdentification identifyMultitasking(const OptionValues& options, const std::string& errorsOut) {
  const OptionReader read(multitaskingSchema(), options);
  MultitaskingIdentification r;
  r.input = loadSeed002Eccentricities(*read.text("data"));
  try {
    r.deviations = identifySeed002(r.input.eccentricities, r.input.setup);
  } catch (const InvalidInput& e) {
    throw InputError({r.input.file, r.input.setupLine, "setup"}, e.what());
  }
  if (!errorsOut.empty()) writeFileAtomically(errorsOut, multitaskingErrorsYaml(r), "errors_out");
  return r;
}

nlohmann::json toJson(const MultitaskingIdentification& r) {
  nlohmann::json j;
  j["file"] = r.input.file;
  const auto& s = r.input.setup;
  j["setup_mm"] = {{"R_B", s.rB}, {"R_B2", s.rB2}, {"R_C", s.rC}, {"Z_C", s.zC}, {"Z_C2", s.zC1}};
  for (const auto& [name, value] : named(r.deviations)) {
    const bool length = isLength(name);
    j["deviations"][name] = {{"value", length ? value * 1e3 : value / kArcsec},
                             {"unit", length ? "um" : "arcsec"},
                             {"iso", findAlias(name)->isoExpression()}};
  }
  return j;
}

std::string multitaskingErrorsYaml(const MultitaskingIdentification& r) {
  std::string y = fmt::format("# The twelve location errors of seed 002 §5.2 (Eqs 17-28) from {}\n"
                              "# (seed 002's names, Table 1; mtacc reads them as the ISO errors docs/conventions.md gives).\n"
                              "errors:\n",
                              r.input.file);
  for (const auto& [name, value] : named(r.deviations))
    y += isLength(name) ? fmt::format("  {}: {:.17g} um\n", name, value * 1e3) : fmt::format("  {}: {:.17g} arcsec\n", name, value / kArcsec);
  return y;
}

}  // namespace mtacc
