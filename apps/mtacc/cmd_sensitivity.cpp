// mtacc sensitivity: how every error parameter moves the TCP at one pose (analytic Jacobian)
// and the sensitivity coefficient k = E / epsilon of seed 001 eq. 15 along a direction.
#include <fmt/format.h>

#include <sstream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/kinematics/budget.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc::cli {
namespace {

struct SensitivityOptions : MachineOptions {
  std::string pose;
  std::string direction;
  std::string params;
  std::string epsilonLength = "10 um";
  std::string epsilonAngle = "30 urad";
};

void run(const SensitivityOptions& o) {
  const auto loaded = load(o);
  const Machine& m = *loaded.machine;
  const auto q = parsePose(m, o.pose);
  const auto model = compile(loaded.machine, loaded.errors);
  const auto tp = toolPoint(compileNominal(loaded.machine), q.data());
  const Vec3 direction = o.direction.empty() ? tp.direction : parseVector(o.direction, "--direction");
  if (direction.norm() < 1e-12) throw InputError(InputLocation{"", 0, "--direction"}, "direction has zero length");
  const double epsLength = parseQuantityArg(o.epsilonLength, Dimension::Length, "--epsilon-length");
  const double epsAngle = parseQuantityArg(o.epsilonAngle, Dimension::Angle, "--epsilon-angle");

  std::vector<Parameter> params;
  if (o.params.empty()) {
    params = parameterCatalogue(m, loaded.errors);
  } else {
    std::stringstream ss(o.params);
    std::string name;
    while (std::getline(ss, name, ',')) {
      try {
        params.push_back(findParameter(m, loaded.errors, name));
      } catch (const std::invalid_argument& e) {
        throw InputError(InputLocation{"", 0, "--params"}, e.what());
      }
    }
  }
  const auto jac = parameterJacobian(model, params, q.data());
  const Vec3 n = direction.normalized();

  nlohmann::json j;
  j["machine"] = m.name;
  j["pose"] = poseJson(m, q.data());
  j["direction"] = {n.x(), n.y(), n.z()};
  j["units"] = "position rows in um per parameter unit (um or urad), orientation rows in urad per unit; "
               "k = E/epsilon along the direction";
  std::string human = fmt::format("Sensitivities at {}; direction ({:.4f}, {:.4f}, {:.4f})\n", formatPose(m, q.data()),
                                  n.x(), n.y(), n.z());
  human += fmt::format("{:<12} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10}\n", "parameter", "dx", "dy", "dz", "ea",
                       "eb", "ec", "k (1st)", "k=E/eps");
  std::string csv = "parameter,unit,dx,dy,dz,ea,eb,ec,k_first_order,k_exact\n";
  for (size_t k = 0; k < params.size(); ++k) {
    const auto& p = params[k];
    // Per unit of the parameter in its display unit: um/um or um/urad (= mm/mm or mm/mrad ...).
    const double unitScale = p.dimension == Dimension::Length ? 1.0 : 1e-3;
    const Vec6 col = jac.col(static_cast<Eigen::Index>(k));
    const Vec3 dpos = col.head<3>() * unitScale;
    const Vec3 drot = col.tail<3>() * (p.dimension == Dimension::Length ? 1e3 : 1.0);
    const double kFirst = n.dot(col.head<3>());
    const double eps = p.dimension == Dimension::Length ? epsLength : epsAngle;
    const double kExact = sensitivityCoefficient(loaded.machine, loaded.errors, p, eps, q.data(), n);
    const double kScale = p.dimension == Dimension::Length ? 1.0 : 1e-3;
    human += fmt::format("{:<12} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:9.4f} {:10.4f} {:10.4f}  {}/{}\n", p.name,
                         dpos.x(), dpos.y(), dpos.z(), drot.x(), drot.y(), drot.z(), kFirst * kScale, kExact * kScale,
                         "um", unitOf(p.dimension));
    csv += fmt::format("{},um/{},{},{},{},{},{},{},{},{}\n", p.name, unitOf(p.dimension), dpos.x(), dpos.y(), dpos.z(),
                       drot.x(), drot.y(), drot.z(), kFirst * kScale, kExact * kScale);
    j["parameters"].push_back({{"name", p.name},
                               {"unit", "um/" + unitOf(p.dimension)},
                               {"position", {dpos.x(), dpos.y(), dpos.z()}},
                               {"orientation", {drot.x(), drot.y(), drot.z()}},
                               {"k_first_order", kFirst * kScale},
                               {"k_exact", kExact * kScale}});
  }
  emit(o, j, human, csv);
}

}  // namespace

void addSensitivityCommand(CLI::App& app) {
  auto o = std::make_shared<SensitivityOptions>();
  auto* cmd = app.add_subcommand("sensitivity", "TCP sensitivity to every error parameter at one pose");
  addMachineOptions(*cmd, *o);
  cmd->add_option("--pose", o->pose, "axis positions, e.g. X=10,Y=0,Z=5,B=-15,C=30 (mm, deg)")->required();
  cmd->add_option("--direction", o->direction, "direction of E (surface normal) i,j,k in the workpiece frame; default: tool direction");
  cmd->add_option("--params", o->params, "comma-separated parameter names or aliases; default: all");
  cmd->add_option("--epsilon-length", o->epsilonLength, "epsilon of length parameters for k = E/eps (default 10 um)");
  cmd->add_option("--epsilon-angle", o->epsilonAngle, "epsilon of angular parameters for k = E/eps (default 30 urad)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mtacc::cli
