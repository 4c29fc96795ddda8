#pragma once
// The options of `fk`, `errors` and `ik`, declared once. The CLI takes its poses and targets as
// text or a file; Python gives them as arrays and the rest of the options by the same keys.
#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/kinematics_batch.hpp"

namespace mtacc {

const OptionSchema& forwardSchema();  // pose, poses (a file), nominal, threads
const OptionSchema& errorsSchema();   // pose, poses, with_tcp (the printed columns), threads
const OptionSchema& inverseSchema();  // tcp, tool, targets (a file), branch, near, with_errors, all

// `schema` is forwardSchema() or errorsSchema().
ForwardOptions forwardOptions(const OptionSchema& schema, const OptionValues& values);
// The poses the values give, one (pose) or a file's (poses): exactly one of the two.
ForwardResult forwardKinematicsOf(const MachineSetup& setup, const OptionSchema& schema, const OptionValues& values);

// How to solve (branch, near, with_errors, all), the targets left to the caller.
InverseRequest inverseSolving(const MachineSetup& setup, const OptionValues& values);
// With the targets the values give: one tcp (with its tool) or a targets file, exactly one.
InverseRequest inverseRequest(const MachineSetup& setup, const OptionValues& values);

}  // namespace mtacc
