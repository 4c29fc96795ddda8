#include "mtacc/workflows/budget.hpp"

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {

const OptionSchema& budgetSchema() {
  static const OptionSchema schema{
      "budget",
      {{.key = "samples", .kind = OptionKind::Count, .help = "positions per axis across its travel", .defaultText = "5", .low = 2,
        .high = 50, .outOfRange = "must be between 2 and 50"},
       {.key = "length", .kind = OptionKind::Quantity,
        .help = "budget every length error at this magnitude (with angle: every location and component error as a constant); "
                "default: each non-zero error of the machine at its own value",
        .dimension = Dimension::Length},
       {.key = "angle", .kind = OptionKind::Quantity, .help = "budget every angular error at this magnitude", .dimension = Dimension::Angle},
       threadsOption()}};
  return schema;
}

BudgetOptions budgetOptions(const OptionValues& values) {
  const OptionReader read(budgetSchema(), values);
  BudgetOptions o;
  o.samplesPerAxis = *read.count("samples");
  o.length = read.quantity("length");
  o.angle = read.quantity("angle");
  o.threads = *read.count("threads");
  return o;
}

JointMatrix workingVolumeGrid(const MachineSetup& setup, int samples) {
  requireInRange(budgetSchema().at("samples"), samples);
  return workingVolumeGrid(*setup.machine, samples);
}

BudgetResult errorBudget(const MachineSetup& setup, const BudgetOptions& o) {
  const Machine& m = *setup.machine;
  requireInRange(budgetSchema().at("samples"), o.samplesPerAxis);
  requireInRange(budgetSchema().at("threads"), o.threads);
  BudgetResult r;
  r.machine = setup.machine;
  r.samplesPerAxis = o.samplesPerAxis;
  r.atMagnitude = o.length || o.angle || nonZeroParameters(m, setup.errors).empty();
  std::vector<BudgetItem> items;
  if (r.atMagnitude) {
    r.length = o.length.value_or(0.01);
    r.angle = o.angle.value_or(30e-6);
    items = budgetItemsAtMagnitude(m, r.length, r.angle);
  } else {
    items = budgetItemsOfModel(m, setup.errors);
  }
  r.grid = workingVolumeGrid(m, o.samplesPerAxis);
  r.entries = errorBudget(setup.machine, items, r.grid, o.threads, o.progress);
  const auto combined = toolErrors(setup.actual(), setup.nominal(), {r.grid, {}}, o.threads);
  for (Eigen::Index i = 0; i < combined.rows(); ++i)
    r.combinedMaxPositionError = std::max(r.combinedMaxPositionError, combined.row(i).head<3>().norm());
  return r;
}

std::string basisText(const BudgetResult& r) {
  if (!r.atMagnitude) return "each non-zero error of the machine's error description, alone, at its value";
  return fmt::format("every location error and every component error as a constant, at {:g} um / {:g} urad", r.length * 1e3,
                     r.angle * 1e6);
}

nlohmann::json toJson(const BudgetResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine->name;
  j["basis"] = r.atMagnitude ? "magnitude" : "model";
  j["basis_text"] = basisText(r);
  j["poses"] = r.grid.rows();
  j["samples_per_axis"] = r.samplesPerAxis;
  j["combined_max_position_error_um"] = r.combinedMaxPositionError * 1e3;
  j["entries"] = nlohmann::json::array();
  for (const auto& e : r.entries)
    j["entries"].push_back({{"error", e.name},
                            {"magnitude", toDisplay(e.magnitude, e.dimension)},
                            {"unit", displayUnit(e.dimension)},
                            {"max_position_error_um", e.maxPositionError * 1e3},
                            {"max_orientation_error_urad", e.maxOrientationError * 1e6},
                            {"worst_pose", poseJson(*r.machine, e.worstPose.data())}});
  return j;
}

namespace {

// The step of k = E / epsilon: a location error or a term's amplitude moves by the requested
// length or angle; a coefficient whose basis is a power of the position (a piecewise or
// polynomial coefficient, per mm or mm^2) by as much as makes the error function move by that
// length or angle at this pose, so that the step stays in the linear range.
double parameterStep(const Machine& m, const ErrorModel& errors, const Parameter& p, const double* q, double step) {
  if (p.kind != ParameterKind::Motion || p.axis >= m.commandedCount()) return step;
  const auto& f = errors.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)];
  const double basis = std::abs(f.basis(p.index, q[p.axis], 0));
  return basis > 1.0 ? step / basis : step;
}

}  // namespace

const OptionSchema& sensitivitySchema() {
  static const OptionSchema schema{
      "sensitivity",
      {{.key = "pose", .kind = OptionKind::Text, .help = "axis positions, e.g. X=10,Y=0,Z=5,B=-15,C=30 (mm, deg)", .required = true},
       {"direction", OptionKind::Text, "direction of E (surface normal) i,j,k in the workpiece frame; default: tool direction"},
       {"parameters", OptionKind::List, "parameter names or aliases; default: all"},
       {"epsilon_length", OptionKind::Quantity, "epsilon of length parameters for k = E/eps", "10 um"},
       {.key = "epsilon_angle", .kind = OptionKind::Quantity, .help = "epsilon of angular parameters for k = E/eps", .defaultText = "30 urad",
        .dimension = Dimension::Angle}}};
  return schema;
}

SensitivityRequest sensitivityRequest(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(sensitivitySchema(), values);
  SensitivityRequest r;
  r.q = poseFromText(setup, *read.text("pose"), "pose");
  if (const auto direction = read.text("direction")) r.direction = parseVector(*direction, "direction");
  r.parameters = read.list("parameters");
  r.epsilonLength = *read.quantity("epsilon_length");
  r.epsilonAngle = *read.quantity("epsilon_angle");
  return r;
}

SensitivityResult sensitivities(const MachineSetup& setup, const SensitivityRequest& request) {
  const Machine& m = *setup.machine;
  if (request.q.size() != static_cast<size_t>(m.commandedCount()))
    throw InputError(InputLocation{"", 0, "pose"}, "expected " + std::to_string(m.commandedCount()) + " axis positions");
  if (const auto violation = m.travelViolation(request.q); !violation.empty())
    throw InputError(InputLocation{"", 0, "pose"}, "pose " + violation);
  if (!(request.epsilonLength >= 1e-6 && request.epsilonLength <= 1.0))
    throw InputError(InputLocation{"", 0, "epsilon_length"}, "must be from 1 nm to 1 mm");
  if (!(request.epsilonAngle >= 1e-9 && request.epsilonAngle <= 1e-3))
    throw InputError(InputLocation{"", 0, "epsilon_angle"}, "must be from 0.001 urad to 1 mrad");
  const auto tp = toolPoint(setup.nominal(), request.q.data());
  const Vec3 direction = request.direction.value_or(tp.direction);
  if (direction.norm() < 1e-12) throw InputError(InputLocation{"", 0, "direction"}, "direction has zero length");
  const auto params = request.parameters.empty() ? parameterCatalogue(m, setup.errors) : findParameters(setup, request.parameters);
  const auto jac = parameterJacobian(compile(setup.machine, setup.errors, params), setup.nominal(), request.q.data());
  SensitivityResult r{setup.machine, request.q, direction.normalized(), {}};
  for (size_t k = 0; k < params.size(); ++k) {
    const auto& p = params[k];
    const bool length = p.dimension == Dimension::Length;
    // Per unit of the parameter in its display unit: um/um or um/urad.
    const double perUnit = length ? 1.0 : 1e-3;
    const Vec6 col = jac.col(static_cast<Eigen::Index>(k));
    const double eps = parameterStep(m, setup.errors, p, request.q.data(), length ? request.epsilonLength : request.epsilonAngle);
    r.rows.push_back({p, col.head<3>() * perUnit, col.tail<3>() * (length ? 1e3 : 1.0), r.direction.dot(col.head<3>()) * perUnit,
                      sensitivityCoefficient(setup.machine, setup.errors, {p, eps}, {request.q.data(), r.direction}) * perUnit});
  }
  return r;
}

double sensitivityCoefficientAt(const MachineSetup& setup, const std::vector<double>& q, const std::string& name, double epsilon,
                                const Vec3& direction) {
  const Parameter p = findParameter(*setup.machine, setup.errors, name);
  if (epsilon == 0.0) throw InputError(InputLocation{"", 0, "epsilon"}, "must not be zero");
  if (!(direction.norm() > 1e-12)) throw InputError(InputLocation{"", 0, "direction"}, "has zero length");
  if (const auto violation = setup.machine->travelViolation(q); !violation.empty())
    throw InputError(InputLocation{"", 0, "pose"}, "pose " + violation);
  return sensitivityCoefficient(setup.machine, setup.errors, {p, epsilon}, {q.data(), direction});
}

nlohmann::json toJson(const SensitivityResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine->name;
  j["pose"] = poseJson(*r.machine, r.q.data());
  j["direction"] = vectorJson(r.direction);
  j["units"] = "position rows in um per parameter unit (um or urad), orientation rows in urad per unit; "
               "k = E/epsilon along the direction";
  j["parameters"] = nlohmann::json::array();
  for (const auto& row : r.rows)
    j["parameters"].push_back({{"name", row.parameter.name},
                               {"unit", std::string("um/") + displayUnit(row.parameter.dimension)},
                               {"position", vectorJson(row.position)},
                               {"orientation", vectorJson(row.orientation)},
                               {"k_first_order", row.kFirstOrder},
                               {"k_exact", row.kExact}});
  return j;
}

}  // namespace mtacc
