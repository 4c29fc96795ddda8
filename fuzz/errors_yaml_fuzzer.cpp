// An errors file for the tilting table, compiled and evaluated at its reference pose, and the
// covariance of its identification record read against it.
#include "fuzz_input.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/identification_record.hpp"
#include "mtacc/kinematics/forward.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("tilting-table");
  return fuzz::asTheFrontEndsDo([&] {
    const auto text = fuzz::text(data, size);
    const auto errors = parseErrors(*machine, text, "fuzz.yaml");
    const auto model = compile(machine, errors);
    toolPoint(model, machine->referencePose.data());
    parseParameterCovariance(*machine, errors, text, "fuzz.yaml");
  });
}
