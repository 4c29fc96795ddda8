// A machine file with its errors, compiled and evaluated at the zero pose.
#include "fuzz_input.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const std::string text = fuzz::text(data, size);
    const auto machine = std::make_shared<const Machine>(parseMachine(text, "fuzz.yaml"));
    const auto model = compile(machine, parseErrors(*machine, text, "fuzz.yaml"));
    const std::vector<double> q(static_cast<size_t>(machine->commandedCount()), 0.0);
    toolPoint(model, q.data());
  });
}
