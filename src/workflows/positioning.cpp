#include "mtacc/workflows/positioning.hpp"

#include "mtacc/core/units.hpp"
#include "mtacc/io/positioning_files.hpp"

namespace mtacc {

PositioningUnits positioningUnits(PositioningAxis axis) {
  if (axis == PositioningAxis::Linear) return {1e3, "um", 1.0, "mm"};
  return {1.0 / kArcsec, "arcsec", 1.0 / kDeg, "deg"};
}

const OptionSchema& positioningSchema() {
  static const OptionSchema schema{
      "positioning",
      {{.key = "data", .kind = OptionKind::Text, .help = "ISO 230-2 KEY=value file or CSV target,cycle,forward,backward (docs/file-formats.md)",
        .positional = true}}};
  return schema;
}

PositioningEvaluation evaluatePositioningFile(const std::string& path) {
  PositioningEvaluation e;
  e.file = path;
  e.test = readPositioningTest(path);
  e.result = evaluatePositioning(e.test);
  return e;
}

nlohmann::json toJson(const PositioningEvaluation& e) {
  const auto u = positioningUnits(e.test.axis);
  const auto& r = e.result;
  const double s = u.deviationScale;
  nlohmann::json j;
  j["file"] = e.file;
  j["name"] = e.test.name;
  j["axis"] = e.test.axis == PositioningAxis::Linear ? "linear" : "rotary";
  j["unit"] = u.deviation;
  j["target_unit"] = u.target;
  j["cycles"] = r.cycles;
  j["notes"] = r.notes;
  auto rows = [&](const Eigen::MatrixXd& x) {
    nlohmann::json out = nlohmann::json::array();
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      std::vector<double> row;
      for (Eigen::Index k = 0; k < x.cols(); ++k) row.push_back(x(i, k) * s);
      out.push_back(row);
    }
    return out;
  };
  j["deviations_forward"] = rows(e.test.forward);
  j["deviations_backward"] = rows(e.test.backward);
  nlohmann::json positions = nlohmann::json::array();
  for (const auto& p : r.positions)
    positions.push_back({{"target", p.target * u.targetScale},
                         {"mean_forward", p.meanForward * s},
                         {"mean_backward", p.meanBackward * s},
                         {"mean", p.mean * s},
                         {"reversal", p.reversal * s},
                         {"s_forward", p.sForward * s},
                         {"s_backward", p.sBackward * s},
                         {"repeatability_forward", p.repeatabilityForward * s},
                         {"repeatability_backward", p.repeatabilityBackward * s},
                         {"repeatability", p.repeatability * s}});
  j["positions"] = positions;
  j["axis_values"] = {{"A_forward", r.accuracyForward * s},
                      {"A_backward", r.accuracyBackward * s},
                      {"A", r.accuracy * s},
                      {"B", r.reversal * s},
                      {"B_mean", r.meanReversal * s},
                      {"E_forward", r.systematicForward * s},
                      {"E_backward", r.systematicBackward * s},
                      {"E", r.systematic * s},
                      {"M", r.meanDeviationRange * s},
                      {"R_forward", r.repeatabilityForward * s},
                      {"R_backward", r.repeatabilityBackward * s},
                      {"R", r.repeatability * s}};
  return j;
}

}  // namespace mtacc
