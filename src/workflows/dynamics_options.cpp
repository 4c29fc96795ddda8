#include "mtacc/workflows/dynamics_options.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"

namespace mtacc {
namespace {

const OptionSchema& dynamicsSchema() {
  static const OptionSchema schema{
      "dynamics",
      {{"at", OptionKind::Text, "Axis positions in mm, e.g. Y=400,Z=-300 (others 0)"},
       {.key = "count", .kind = OptionKind::Count, .help = "Modes to list", .defaultText = "12", .low = 1, .high = 100000,
        .outOfRange = "must be from 1 to 100000"},
       {"from", OptionKind::Number, "First frequency, Hz", "0"},
       {"to", OptionKind::Number, "Last frequency, Hz", "200"},
       {"step", OptionKind::Number, "Frequency step, Hz", "1"},
       {"method", OptionKind::Text, "auto (the modal sum where the damping is proportional, else direct), modal or direct", "auto"},
       {"quantity", OptionKind::Text, "Hx/X (um/g), Cxx (um/N) or f1 (Hz)", "Hx/X"},
       {"axes", OptionKind::List, "The two axes of the grid", "Y,Z"},
       {"grid", OptionKind::Text, "Positions per axis, each 2 to 1000", "20x20"},
       {"compare", OptionKind::Text, "A second model evaluated on the same grid"}}};
  return schema;
}

}  // namespace

const OptionSchema& structureModesSchema() {
  static const OptionSchema schema = dynamicsSchema().subset("dynamics modes", {"at", "count"});
  return schema;
}

const OptionSchema& structureFrfSchema() {
  static const OptionSchema schema = dynamicsSchema().subset("dynamics frf", {"at", "from", "to", "step", "method"});
  return schema;
}

const OptionSchema& structureAccelerationSchema() {
  static const OptionSchema schema = dynamicsSchema().subset("dynamics accel", {"at"});
  return schema;
}

const OptionSchema& structureMapSchema() {
  static const OptionSchema schema = dynamicsSchema().subset("dynamics map", {"at", "quantity", "axes", "grid", "compare"});
  return schema;
}

std::vector<double> structurePositionsOf(const StructureModel& model, const OptionSchema& schema, const OptionValues& values) {
  return structurePositions(model, OptionReader(schema, values).text("at").value_or(""));
}

int modesCount(const OptionValues& values) { return *OptionReader(structureModesSchema(), values).count("count"); }

FrfRequest structureFrfRequest(const StructureModel& model, const OptionValues& values) {
  const OptionReader read(structureFrfSchema(), values);
  FrfRequest r;
  r.positions = structurePositionsOf(model, structureFrfSchema(), values);
  r.frequencies = frequencyGrid(*read.number("from"), *read.number("to"), *read.number("step"));
  r.method = *read.text("method");
  return r;
}

MapRequest structureMapRequest(const StructureModel& model, const OptionValues& values) {
  const OptionReader read(structureMapSchema(), values);
  const auto axes = read.list("axes");
  const auto grid = splitList(*read.text("grid"), 'x');
  if (axes.size() != 2) throw InputError(InputLocation{"", 0, "axes"}, "expected two axes, e.g. Y,Z");
  if (grid.size() != 2) throw InputError(InputLocation{"", 0, "grid"}, "expected the positions along each axis, e.g. 20x20");
  return {*read.text("quantity"),
          {axes[0], axes[1], parseCount(grid[0], "grid", 2, 1000), parseCount(grid[1], "grid", 2, 1000),
           structurePositionsOf(model, structureMapSchema(), values)}};
}

std::optional<std::string> mapComparison(const OptionValues& values) { return OptionReader(structureMapSchema(), values).text("compare"); }

}  // namespace mtacc
