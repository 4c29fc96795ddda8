#include "mtacc/identification/acting_alike.hpp"

#include <random>

#include <fmt/format.h>

#include "mtacc/core/units.hpp"
#include "mtacc/identification/observability.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {
namespace {

constexpr int kWorkspacePoses = 64;

// Random poses within travel (a continuous axis over one turn), the same on every run.
std::vector<std::vector<double>> workspacePoses(const Machine& m) {
  std::mt19937 rng(20261126);
  std::vector<std::vector<double>> poses(kWorkspacePoses);
  for (auto& q : poses)
    for (const auto& a : m.axes) {
      if (!a.commanded()) continue;
      const Travel t = a.travel.value_or(Travel{-kPi, kPi});
      q.push_back(std::uniform_real_distribution<double>(t.min, t.max)(rng));
    }
  return poses;
}

}  // namespace

std::vector<std::string> locationErrorsActingAlike(const std::shared_ptr<const Machine>& machine, const std::vector<Parameter>& catalogue) {
  std::vector<Parameter> location;
  for (const auto& p : catalogue)
    if (p.kind == ParameterKind::Location) location.push_back(p);
  if (location.empty()) return {};
  const auto model = compile(machine, ErrorModel::zero(*machine), location);
  const auto nominal = compileNominal(machine);
  const auto poses = workspacePoses(*machine);
  const auto n = static_cast<Eigen::Index>(location.size());
  Eigen::MatrixXd jacobian(6 * static_cast<Eigen::Index>(poses.size()), n);
  for (size_t i = 0; i < poses.size(); ++i)
    jacobian.middleRows(6 * static_cast<Eigen::Index>(i), 6) = parameterJacobian(model, nominal, poses[i].data());
  const Eigen::VectorXd norms = jacobian.colwise().norm().transpose();
  Eigen::VectorXd typical(n);
  for (Eigen::Index k = 0; k < n; ++k) typical[k] = location[static_cast<size_t>(k)].dimension == Dimension::Length ? 1e-3 : 1e-5;
  const double largestEffect = (norms.array() * typical.array()).maxCoeff();
  std::vector<std::string> findings, kept;
  std::vector<Eigen::Index> keptColumns;
  std::vector<bool> placed(static_cast<size_t>(n), false);
  auto hasEffect = [&](Eigen::Index k) { return norms[k] * typical[k] > kRankTolerance * largestEffect; };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (placed[static_cast<size_t>(i)] || !hasEffect(i)) continue;
    const std::string& first = location[static_cast<size_t>(i)].name;
    std::vector<std::string> members{first};
    std::string effect = first;
    bool scaled = false;
    for (Eigen::Index j = i + 1; j < n; ++j) {
      if (placed[static_cast<size_t>(j)] || !hasEffect(j)) continue;
      const double cosine = jacobian.col(i).dot(jacobian.col(j)) / (norms[i] * norms[j]);
      if (std::abs(cosine) < 1.0 - 1e-10) continue;
      placed[static_cast<size_t>(j)] = true;
      members.push_back(location[static_cast<size_t>(j)].name);
      // A unit of the first parameter has the effect of `ratio` units of this one.
      const double ratio = std::copysign(norms[i] / norms[j], cosine);
      const bool unit = std::abs(std::abs(ratio) - 1.0) < 1e-6;
      scaled = scaled || !unit;
      effect += fmt::format(" = {}{}{}", ratio < 0 ? "-" : "", unit ? "" : fmt::format("{:.4g} ", std::abs(ratio)), members.back());
    }
    if (members.size() > 1) {
      std::string list = members[0];
      for (size_t k = 1; k < members.size(); ++k) list += (k + 1 == members.size() ? " and " : ", ") + members[k];
      findings.push_back(fmt::format("{} act alike ({} in effect{})", list, effect, scaled ? "; lengths in mm, angles in rad" : ""));
    }
    kept.push_back(first);
    keptColumns.push_back(i);
  }
  Eigen::MatrixXd rest(jacobian.rows(), static_cast<Eigen::Index>(keptColumns.size()));
  Eigen::VectorXd restTypical(rest.cols());
  for (size_t k = 0; k < keptColumns.size(); ++k) {
    rest.col(static_cast<Eigen::Index>(k)) = jacobian.col(keptColumns[k]);
    restTypical[static_cast<Eigen::Index>(k)] = typical[keptColumns[k]];
  }
  for (Eigen::Index k = 0; k < n; ++k)
    if (!hasEffect(k)) findings.push_back(location[static_cast<size_t>(k)].name + " has no effect on this machine");
  for (auto& f : analyseObservability(std::move(rest), kept, restTypical, kRankTolerance, 1).findings("this machine"))
    findings.push_back(std::move(f));
  return findings;
}

}  // namespace mtacc
