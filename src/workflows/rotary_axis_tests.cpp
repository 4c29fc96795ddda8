#include "mtacc/workflows/rotary_axis_tests.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/standard_paths.hpp"

namespace mtacc {
namespace {

// A result's sensitivity below this (um per um or per urad) is a second-order effect, not seen.
constexpr double kSeen = 1e-3;


}  // namespace

const OptionSchema& rotaryTestsSchema() {
  static const OptionSchema schema{
      "rotary-tests",
      {{"axes", OptionKind::List, "the rotary axes to test; default: every commanded rotary axis"},
       {.key = "radius", .kind = OptionKind::Quantity, .help = "a table axis's sphere (work ball) from its line", .defaultText = "100 mm",
        .low = 1.0, .high = 2000.0, .outOfRange = "must be from 1 mm to 2 m"},
       {.key = "spread", .kind = OptionKind::Quantity,
        .help = "the second R-test set-up: the sphere this far along a table axis's line, the tool ball this far beyond the tip on a head axis",
        .defaultText = "100 mm", .low = 1.0, .high = 2000.0, .outOfRange = "must be from 1 mm to 2 m"},
       {.key = "length", .kind = OptionKind::Quantity, .help = "ballbar length", .defaultText = "100 mm", .low = 10.0, .high = 1500.0,
        .outOfRange = "must be from 10 mm to 1.5 m"},
       {.key = "positions", .kind = OptionKind::Count, .help = "R-test positions over the sweep", .defaultText = "36", .low = 3, .high = 3600,
        .outOfRange = "must be from 3 to 3600"},
       {.key = "points", .kind = OptionKind::Count, .help = "ballbar readings over the sweep", .defaultText = "360", .low = 8,
        .high = kMaxPointsPerRun, .outOfRange = "must be from 8 to 100000"},
       {.key = "feed", .kind = OptionKind::Number, .help = "feed of the programs (mm/min)", .defaultText = "1000", .low = 1, .high = 1e5,
        .outOfRange = "must be from 1 to 100000 mm/min"},
       {"plan_out", OptionKind::Text, "write the tests as a plan (YAML) that simulate, observability and identify read"},
       {"programs", OptionKind::Text, "write a G-code program per test into this folder (<test>.nc)"},
       {.key = "decimals", .kind = OptionKind::Count, .help = "decimal places of the programs' positions (mm, deg): the controller's limit",
        .defaultText = "6", .low = 3, .high = 12, .outOfRange = "must be from 3 to 12"}}};
  return schema;
}

RotaryTestsRequest rotaryTestsRequest(const OptionValues& values) {
  const OptionReader r(rotaryTestsSchema(), values);
  RotaryTestsRequest q;
  q.options.axes = r.list("axes");
  q.options.radius = *r.quantity("radius");
  q.options.spread = *r.quantity("spread");
  q.options.ballbarLength = *r.quantity("length");
  q.options.rtestPositions = *r.count("positions");
  q.options.ballbarPoints = *r.count("points");
  q.options.feed = *r.number("feed");
  q.planOut = r.text("plan_out");
  q.programsDir = r.text("programs");
  q.decimals = *r.count("decimals");
  return q;
}

std::string rotaryTestsPlan(const std::string& machineName, const RotaryAxisTestSet& set) {
  std::string plan = fmt::format("# ISO 10791-6 tests around the rotary axes of {}, written by mtacc rotary-tests.\n", machineName);
  for (const auto& note : set.notes) plan += "# " + note + "\n";
  plan += "name: ISO 10791-6 rotary-axis tests\nruns:\n";
  for (const auto& t : set.tests) plan += t.planEntry;
  return plan;
}

RotaryTestsResult rotaryTestsFor(const MachineSetup& setup, const RotaryTestsRequest& request) {
  const auto nominal = setup.nominal();
  RotaryTestsResult r;
  r.machine = setup.machine->name;
  try {
    r.set = rotaryAxisTests(nominal, request.options);
  } catch (const UnreachableInput& e) {
    throw InputError({"", 0, "radius"}, e.reason());
  } catch (const InvalidInput& e) {
    throw InputError({"", 0, "axes"}, e.reason());
  }
  const auto actual = setup.actual();
  for (const auto& t : r.set.tests) {
    MeasurementRun run = t.run;
    simulateRun(actual, nominal, run);
    r.simulated.push_back(evaluateRotaryTest(nominal, run));
  }
  r.sensitivity = rotaryTestSensitivities(nominal, r.set.tests);
  if (request.programsDir) {
    std::error_code ec;
    std::filesystem::create_directories(*request.programsDir, ec);
    if (ec) throw InputError({"", 0, "programs"}, *request.programsDir + ": cannot create the folder: " + ec.message());
    for (const auto& t : r.set.tests) {
      const std::string path = (std::filesystem::path(*request.programsDir) / (t.name + ".nc")).string();
      writeFileAtomically(path, rotaryTestProgram(*setup.machine, t, request.decimals), "programs");
      r.written.push_back(path);
    }
  }
  if (request.planOut) {
    writeFileAtomically(*request.planOut, rotaryTestsPlan(r.machine, r.set), "plan_out");
    r.written.push_back(*request.planOut);
  }
  return r;
}

nlohmann::json toJson(const RotaryTestsResult& r) {
  nlohmann::json tests = nlohmann::json::array();
  for (size_t t = 0; t < r.set.tests.size(); ++t) {
    const auto& test = r.set.tests[t];
    const auto& run = test.run;
    nlohmann::json results = nlohmann::json::object();
    for (size_t q = 0; q < r.simulated[t].quantities.size(); ++q) {
      nlohmann::json sees = nlohmann::json::array();
      std::vector<std::pair<double, size_t>> order;
      for (size_t k = 0; k < r.sensitivity.parameters.size(); ++k)
        if (r.sensitivity.perTest[t][q][k] > kSeen) order.emplace_back(-r.sensitivity.perTest[t][q][k], k);
      std::sort(order.begin(), order.end());
      for (const auto& [minus, k] : order) {
        const auto& p = r.sensitivity.parameters[k];
        sees.push_back({{"parameter", p.name}, {"range_per_unit", -minus}, {"unit", p.dimension == Dimension::Length ? "um/um" : "um/urad"}});
      }
      results[r.simulated[t].quantities[q]] = {{"range_um", r.simulated[t].ranges[q] / kMicro}, {"sees", sees}};
    }
    nlohmann::json setUp = {{"instrument", instrumentName(run.instrument)},
                            {"sphere_mm", vectorJson(run.setup.target)},
                            {"tool_ball_mm", vectorJson(run.setup.toolBall)}};
    if (run.instrument == Instrument::Ballbar) setUp["length_mm"] = run.setup.length;
    tests.push_back({{"name", test.name},
                     {"axis", test.axis},
                     {"kind", test.kind == RotaryTestKind::RTest ? std::string("rtest") : std::string("ballbar ") + toString(test.kind)},
                     {"description", test.description},
                     {"from_deg", test.from / kDeg},
                     {"to_deg", test.to / kDeg},
                     {"poses", run.poses()},
                     {"set_up", setUp},
                     {"results", results}});
  }
  return {{"machine", r.machine}, {"tests", tests}, {"notes", r.set.notes}, {"written", r.written},
          {"seen_above", {{"value", kSeen}, {"unit", "um per um or urad"}}}};
}

}  // namespace mtacc
