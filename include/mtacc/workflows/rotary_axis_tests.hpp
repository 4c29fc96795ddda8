#pragma once
// Workflow `rotary-tests` (alias `iso10791-6`): the ISO 10791-6 tests around each rotary axis of a
// machine — their set-ups, the plan that `simulate`, `observability` and `identify` read, a
// program per test, the results they show on the machine with its errors, and which location
// errors each result sees (measurement/rotary_axis_tests.hpp).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/measurement/rotary_axis_tests.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct RotaryTestsRequest {
  RotaryAxisTestOptions options;
  std::optional<std::string> planOut;      // the plan YAML written there
  std::optional<std::string> programsDir;  // a G-code program per test written there (<test>.nc)
  int decimals = 6;                        // of the programs' positions
};
// axes, radius, spread, length, positions, points, feed, plan_out, programs, decimals.
const OptionSchema& rotaryTestsSchema();
RotaryTestsRequest rotaryTestsRequest(const OptionValues& values);

struct RotaryTestsResult {
  std::string machine;
  RotaryAxisTestSet set;
  std::vector<RotaryTestResult> simulated;  // per test, on the machine with its errors
  RotaryTestSensitivity sensitivity;
  std::vector<std::string> written;         // the files written
};

// Throws InputError for options out of range or a set-up beyond the travel (naming the test).
RotaryTestsResult rotaryTestsFor(const MachineSetup& setup, const RotaryTestsRequest& request);

// The plan text (docs/file-formats.md "Test plans") of the tests.
std::string rotaryTestsPlan(const std::string& machineName, const RotaryAxisTestSet& set);

// Results in um; per test its set-up (workpiece frame, mm), sweep (deg), what it sees (um per um
// or urad, each location error alone).
nlohmann::json toJson(const RotaryTestsResult& result);

}  // namespace mtacc
