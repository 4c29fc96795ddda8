#include "mtacc/workflows/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/structure_yaml.hpp"

namespace mtacc {
namespace {

nlohmann::json statisticsJson(const BoxStatistics& s) {
  return {{"min", s.min}, {"lower_quartile", s.lowerQuartile}, {"median", s.median},
          {"upper_quartile", s.upperQuartile}, {"max", s.max}};
}

}  // namespace

StructureModel loadStructureModel(const std::string& pathOrName) { return loadStructure(pathOrName); }

nlohmann::json structureJson(const StructureModel& m) {
  auto mm = [](const Vec3& v) { return vectorJson(v * 1e3); };
  nlohmann::json j;
  j["name"] = m.name;
  for (const auto& a : m.axes) j["axes"].push_back({{"name", a.name}, {"travel_mm", {a.min * 1e3, a.max * 1e3}}});
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const auto& b = m.bodies[i];
    std::vector<std::string> movedBy;
    for (const auto& a : m.axes)
      if (std::count(a.moves.begin(), a.moves.end(), static_cast<int>(i))) movedBy.push_back(a.name);
    j["bodies"].push_back({{"name", b.name}, {"mass_kg", b.mass}, {"centre_mm", mm(b.centre)}, {"size_mm", mm(b.size)},
                           {"box_centre_mm", mm(b.boxCentre)}, {"moved_by", movedBy}});
  }
  return j;
}

std::vector<double> structurePositions(const StructureModel& m, const std::string& text, const std::string& key) {
  std::vector<double> q(m.axes.size(), 0.0);
  for (const auto& a : parseAssignments(text, key)) {
    const int j = m.axisIndex(a.name);
    if (j < 0) {
      std::string axes;
      for (const auto& axis : m.axes) axes += (axes.empty() ? "" : ", ") + axis.name;
      throw InputError(InputLocation{"", 0, key}, "'" + a.name + "' is not an axis of " + m.name + " (axes: " + axes + ")");
    }
    q[static_cast<size_t>(j)] = parseNumber(a.value, key + " " + a.name) * 1e-3;
  }
  if (const auto violation = travelViolation(m, q); !violation.empty()) throw InputError(InputLocation{"", 0, key}, violation);
  return q;
}

ModesResult structureModes(const StructureModel& model, const std::vector<double>& positions) {
  ModesResult r;
  r.model = model.name;
  r.matrices = assembleStructure(model, positions);
  r.undamped = undampedModes(model, r.matrices);
  r.damped = dampedModes(r.matrices);
  static const char* kDofs[6] = {"x", "y", "z", "rx", "ry", "rz"};
  for (Eigen::Index k = 0; k < r.undamped.frequencies.size(); ++k) {
    const Eigen::VectorXd phi = r.undamped.shapes.col(k);
    Eigen::Index dof = 0;
    (r.matrices.mass * phi).cwiseProduct(phi).maxCoeff(&dof);
    r.bodies.push_back(model.bodies[static_cast<size_t>(dof / 6)].name);
    r.dofs.push_back(kDofs[dof % 6]);
  }
  return r;
}

nlohmann::json toJson(const ModesResult& r, int count) {
  nlohmann::json j;
  j["model"] = r.model;
  j["modes"] = nlohmann::json::array();
  const auto n = std::min<Eigen::Index>(count, r.undamped.frequencies.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    const DampedMode d = static_cast<size_t>(k) < r.damped.size() ? r.damped[static_cast<size_t>(k)] : DampedMode{0, 0};
    j["modes"].push_back({{"frequency_hz", r.undamped.frequencies[k]}, {"damped_frequency_hz", d.frequency},
                          {"damping_ratio", d.dampingRatio}, {"body", r.bodies[static_cast<size_t>(k)]},
                          {"dof", r.dofs[static_cast<size_t>(k)]},
                          {"shape", std::vector<double>(r.undamped.shapes.col(k).data(),
                                                        r.undamped.shapes.col(k).data() + r.undamped.shapes.rows())}});
  }
  return j;
}

std::vector<double> frequencyGrid(double from, double to, double step) {
  if (!(from >= 0 && from <= 1e9)) throw InputError(InputLocation{"", 0, "from"}, "must be from 0 to 1e9 Hz");
  if (!(to >= from && to <= 1e9)) throw InputError(InputLocation{"", 0, "to"}, "must be from the first frequency to 1e9 Hz");
  if (!(step > 0)) throw InputError(InputLocation{"", 0, "step"}, "must be positive (Hz)");
  const double count = std::floor((to - from) / step + 1e-9) + 1;
  if (count > 1e6) throw InputError(InputLocation{"", 0, "step"}, "more than 1,000,000 frequencies; choose a larger step");
  std::vector<double> f;
  for (int i = 0; i < static_cast<int>(count); ++i) f.push_back(from + i * step);
  return f;
}

FrfResult structureFrf(const StructureModel& model, const FrfRequest& request) {
  for (const double f : request.frequencies)
    if (!(f >= 0 && f <= 1e9)) throw InputError(InputLocation{"", 0, "frequencies"}, fmt::format("{} Hz: expected 0 to 1e9 Hz", f));
  if (request.method != "auto" && request.method != "modal" && request.method != "direct")
    throw InputError(InputLocation{"", 0, "method"}, "expected auto, modal or direct");
  FrfResult r;
  r.model = model.name;
  r.frequencies = request.frequencies;
  const auto mats = assembleStructure(model, request.positions);
  const auto modes = undampedModes(model, mats);
  r.dampingCoupling = modalDampingCoupling(mats, modes);
  // Rounding leaves ~1e-12 of coupling in a proportional damping; a real coupling is percent.
  constexpr double kProportional = 1e-6;
  r.method = request.method == "auto" ? (r.dampingCoupling <= kProportional ? "modal" : "direct") : request.method;
  if (r.method == "modal" && r.dampingCoupling > kProportional)
    r.warnings.push_back(fmt::format("the damping is not proportional (modes coupled up to {:.1f} % by it): the modal sum "
                                     "ignores that coupling; method direct is exact",
                                     100 * r.dampingCoupling));
  r.frf = r.method == "modal" ? frfModal(mats, modes, request.frequencies) : frfDirect(mats, request.frequencies);
  r.staticCompliance = staticCompliance(mats);
  return r;
}

nlohmann::json toJson(const FrfResult& r) {
  static const char* kAxes = "xyz";
  nlohmann::json j;
  j["model"] = r.model;
  j["method"] = r.method;
  j["damping_coupling"] = r.dampingCoupling;
  j["warnings"] = r.warnings;
  j["frf"] = nlohmann::json::array();
  for (size_t s = 0; s < r.frequencies.size(); ++s) {
    nlohmann::json magnitude, phase;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        const auto v = r.frf[s](i, k);
        const std::string term = std::string("H") + kAxes[i] + kAxes[k];
        magnitude[term] = std::abs(v) * 1e6;
        phase[term] = std::arg(v) / kDeg;
      }
    j["frf"].push_back({{"frequency_hz", r.frequencies[s]}, {"magnitude_um_per_n", magnitude}, {"phase_deg", phase}});
  }
  j["static_compliance_um_per_n"] = nlohmann::json::array();
  for (int i = 0; i < 3; ++i)
    j["static_compliance_um_per_n"].push_back({r.staticCompliance(i, 0) * 1e6, r.staticCompliance(i, 1) * 1e6,
                                               r.staticCompliance(i, 2) * 1e6});
  return j;
}

AccelerationResult structureAcceleration(const StructureModel& model, const std::vector<double>& positions) {
  AccelerationResult r;
  r.model = model.name;
  for (const auto& a : model.axes) r.axes.push_back(a.name);
  r.response = accelerationResponse(assembleStructure(model, positions)) * kStandardGravity * 1e6;
  return r;
}

nlohmann::json toJson(const AccelerationResult& r) {
  static const char* kAxes = "xyz";
  nlohmann::json j;
  j["model"] = r.model;
  for (int i = 0; i < 3; ++i)
    for (Eigen::Index k = 0; k < r.response.cols(); ++k)
      j["response_um_per_g"][std::string("H") + kAxes[i]][r.axes[static_cast<size_t>(k)]] = r.response(i, k);
  return j;
}

MapResult structureMap(const StructureModel& model, const MapRequest& request) {
  const MapGrid& g = request.grid;
  if (g.countA < 2 || g.countB < 2 || g.countA > 1000 || g.countB > 1000)
    throw InputError(InputLocation{"", 0, "grid"}, "expected 2 to 1000 positions per axis, e.g. 20x20");
  MapResult r{model.name, dynamicsQuantity(model, request.quantity), {}};
  r.map = dynamicsMap(model, g, r.quantity);
  return r;
}

nlohmann::json toJson(const MapResult& r) {
  nlohmann::json a = nlohmann::json::array(), b = nlohmann::json::array(), values = nlohmann::json::array();
  for (double v : r.map.a) a.push_back(v * 1e3);
  for (double v : r.map.b) b.push_back(v * 1e3);
  for (Eigen::Index i = 0; i < r.map.values.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index k = 0; k < r.map.values.cols(); ++k) row.push_back(r.map.values(i, k));
    values.push_back(row);
  }
  return {{"model", r.model}, {"quantity", r.quantity.name}, {"unit", r.quantity.unit}, {"axes", {r.map.axisA, r.map.axisB}},
          {"a_mm", a}, {"b_mm", b}, {"values", values}, {"statistics", statisticsJson(r.map.statistics)}};
}

}  // namespace mtacc
