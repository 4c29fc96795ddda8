#include "mtacc/workflows/report_paths.hpp"

#include <algorithm>
#include <cmath>

#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"

namespace mtacc {

const OptionSchema& reportSchema() {
  static const OptionSchema schema{
      "report",
      {{"output", OptionKind::Text, "output directory", "."},
       {"errors", OptionKind::Text, "errors file (default: the machine file's)"},
       {.key = "load", .kind = OptionKind::Number,
        .help = "workpiece load in kg for the errors' stiffness changes (default: the errors' workpiece_load)", .low = 0, .high = 1e6,
        .outOfRange = "must be from 0 to 1e6 kg"},
       {"samples", OptionKind::Count, "positions per axis for the error budget", "5"},
       {"plan", OptionKind::Text, "test plan to simulate, evaluate and identify from (e.g. tilting-table-rtest)"},
       {"data", OptionKind::List, "the plan's measured files (CSV) to identify from, instead of simulating the plan"},
       {"structure", OptionKind::Text, "structure model for the dynamics section (e.g. tzyx-arm-x)"},
       {"compare", OptionKind::Text, "a second structure model to compare with (e.g. tzyx-arm-y)"},
       {"positioning", OptionKind::List, "ISO 230-2 positioning-test files for the positioning section"},
       {"plate", OptionKind::List, "plate measurements (the 1991 BCR report) to compare with the model, one section each"},
       {"component", OptionKind::List, "direct-measurement runs (the 1991 BCR report) to fit and plot, one section each"},
       {"drift", OptionKind::List, "thermal drift tests (ISO 230-3, the 1991 BCR report) to evaluate and plot, one section each"},
       {"thermal", OptionKind::Text, "thermal state (YAML: the temperatures along the scales): the whole report is the warm machine's"},
       {"decomposition", OptionKind::Text, "a decomposition set (Andolfatto et al. 2011 recorded signals) for the error-decomposition section"}}};
  return schema;
}
namespace {

double midTravel(const Axis& a) { return a.travel ? 0.5 * (a.travel->min + a.travel->max) : 0.0; }

// The radial component of the TCP error (actual minus nominal) at each pose.
void radialDeviation(const MachineSetup& setup, CirclePathResult& r) {
  const auto errors = toolErrors(setup.actual(), setup.nominal(), {r.q, {}});
  r.radialDeviation.resize(static_cast<size_t>(r.q.rows()));
  for (Eigen::Index i = 0; i < r.q.rows(); ++i)
    r.radialDeviation[static_cast<size_t>(i)] = errors.row(i).head<3>().dot(r.radialDirection.row(i));
}

}  // namespace

std::optional<CirclePathResult> xyCircleTest(const MachineSetup& setup, int points) {
  const Machine& m = *setup.machine;
  const int x = m.axisIndex("X"), y = m.axisIndex("Y"), z = m.axisIndex("Z");
  if (x < 0 || y < 0 || z < 0) return std::nullopt;
  const Axis &ax = m.axes[static_cast<size_t>(x)], &ay = m.axes[static_cast<size_t>(y)];
  if (!ax.travel || !ay.travel) return std::nullopt;
  CirclePathResult r;
  r.machine = setup.machine;
  r.radius = 0.25 * std::min(ax.travel->max - ax.travel->min, ay.travel->max - ay.travel->min);
  r.description = "circle in the X-Y plane around mid-travel, rotary axes at zero (or at the end of a travel that excludes zero)";
  std::vector<double> base(static_cast<size_t>(m.commandedCount()), 0.0);
  for (int k = 0; k < m.commandedCount(); ++k) {
    const Axis& a = m.axes[static_cast<size_t>(k)];
    if (k == x || k == y || k == z) base[static_cast<size_t>(k)] = midTravel(a);
    else if (a.isRotary() && a.travel && !(a.travel->min <= 0 && 0 <= a.travel->max)) base[static_cast<size_t>(k)] = a.travel->min;
  }
  const auto nominal = setup.nominal();
  r.centre = toolPosition(nominal, base.data());
  r.q.resize(points, m.commandedCount());
  r.radialDirection.resize(points, 3);
  for (int i = 0; i < points; ++i) {
    const double phi = 2 * kPi * i / (points - 1);
    r.phi.push_back(phi);
    for (int k = 0; k < m.commandedCount(); ++k) r.q(i, k) = base[static_cast<size_t>(k)];
    r.q(i, x) += r.radius * std::cos(phi);
    r.q(i, y) += r.radius * std::sin(phi);
    r.radialDirection.row(i) = (toolPosition(nominal, r.q.row(i).data()) - r.centre).normalized().transpose();
  }
  radialDeviation(setup, r);
  return r;
}

std::optional<CirclePathResult> tiltedCircleTest(const MachineSetup& setup, int points) {
  const Machine& m = *setup.machine;
  if (std::count_if(m.axes.begin(), m.axes.end(), [](const Axis& a) { return a.type == AxisType::Rotary; }) != 2)
    return std::nullopt;
  CirclePathResult r;
  r.machine = setup.machine;
  r.radius = 40.0;
  r.centre = Vec3(-60.0, 0.0, 50.0);
  r.description = "TCP circle, tool tilted 30 deg towards its centre (a cone-frustum-like 5-axis path)";
  const double tilt = 30 * kDeg;
  std::vector<Vec3> tcps, tools;
  r.radialDirection.resize(points, 3);
  for (int i = 0; i < points; ++i) {
    const double phi = 2 * kPi * i / (points - 1);
    r.phi.push_back(phi);
    const Vec3 radial(std::cos(phi), std::sin(phi), 0.0);
    tcps.push_back(r.centre + r.radius * radial);
    tools.emplace_back(-std::sin(tilt) * radial.x(), -std::sin(tilt) * radial.y(), std::cos(tilt));
    r.radialDirection.row(i) = radial.transpose();
  }
  const auto path = solveIkPath(setup.nominal(), tcps, tools);
  r.q.resize(points, m.commandedCount());
  for (int i = 0; i < points; ++i)
    for (int k = 0; k < m.commandedCount(); ++k) r.q(i, k) = path[static_cast<size_t>(i)].q[static_cast<size_t>(k)];
  radialDeviation(setup, r);
  return r;
}

nlohmann::json toJson(const CirclePathResult& r) {
  const Machine& m = *r.machine;
  nlohmann::json phi = nlohmann::json::array(), q = nlohmann::json::array(), radial = nlohmann::json::array(),
                 deviation = nlohmann::json::array();
  for (size_t i = 0; i < r.phi.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    phi.push_back(r.phi[i] / kDeg);
    nlohmann::json axes = nlohmann::json::array();
    for (int k = 0; k < m.commandedCount(); ++k)
      axes.push_back(m.axes[static_cast<size_t>(k)].isRotary() ? r.q(row, k) / kDeg : r.q(row, k));
    q.push_back(axes);
    radial.push_back(vectorJson(r.radialDirection.row(row).transpose()));
    deviation.push_back(r.radialDeviation[i] * 1e3);
  }
  return {{"machine", m.name}, {"description", r.description}, {"radius_mm", r.radius}, {"centre_mm", vectorJson(r.centre)},
          {"phi_deg", phi}, {"q", q}, {"radial_direction", radial}, {"radial_deviation_um", deviation}};
}

}  // namespace mtacc
