// A thermal state (YAML) for the 3-axis machine: read, added to its errors, compiled and
// evaluated at a pose inside the travel.
#include "fuzz_input.hpp"
#include "mtacc/errors/thermal_state.hpp"
#include "mtacc/io/thermal_state_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("three-axis-vertical");
  return fuzz::asTheFrontEndsDo([&] {
    const auto state = parseThermalState(*machine, fuzz::text(data, size), "fuzz.yaml");
    const auto model = compile(machine, atThermalState(*machine, ErrorModel::zero(*machine), state));
    const double q[3] = {300, 200, 250};
    toolPoint(model, q);
  });
}
