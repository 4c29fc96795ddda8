#pragma once
// The options of `dynamics modes | frf | accel | map`, declared once. The structure model itself
// is the command's argument (the CLI's `model`, Python's Structure), as the machine is for the
// machine's workflows.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/dynamics.hpp"

namespace mtacc {

const OptionSchema& structureModesSchema();         // at, count
const OptionSchema& structureFrfSchema();           // at, from, to, step (Hz), method
const OptionSchema& structureAccelerationSchema();  // at
const OptionSchema& structureMapSchema();           // at, quantity, axes, grid, compare

// The axis positions `at` of `values`, read with `schema` (any of the four), in m.
std::vector<double> structurePositionsOf(const StructureModel& model, const OptionSchema& schema, const OptionValues& values);
int modesCount(const OptionValues& values);
FrfRequest structureFrfRequest(const StructureModel& model, const OptionValues& values);
MapRequest structureMapRequest(const StructureModel& model, const OptionValues& values);
// A second model evaluated on the same grid, when `compare` names one.
std::optional<std::string> mapComparison(const OptionValues& values);

}  // namespace mtacc
