#pragma once
#include <memory>
#include <string>

#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_yaml.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/machine/machine_yaml.hpp"

namespace mtacc::test {

inline std::shared_ptr<const Machine> bundled(const std::string& name) {
  return std::make_shared<const Machine>(loadMachine(name));
}

inline const char* kFiveAxisMachines[] = {"tilting-table", "swivel-head-table", "double-pivot-head",
                                          "inclined-a-table", "multitasking-b-c", "maho"};

}  // namespace mtacc::test
