// An errors file for the tilting table, compiled and evaluated at its reference pose.
#include "fuzz_input.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const auto machine = fuzz::bundled("tilting-table");
  return fuzz::asTheFrontEndsDo([&] {
    const auto model = compile(machine, parseErrors(*machine, fuzz::text(data, size), "fuzz.yaml"));
    toolPoint(model, machine->referencePose.data());
  });
}
