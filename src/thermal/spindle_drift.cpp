#include "mtacc/thermal/spindle_drift.hpp"

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

template <class Evaluate>
Vec6 perDirection(const SpindleDriftModel& model, const Eigen::VectorXd& temperatures, Evaluate evaluate) {
  if (temperatures.size() != static_cast<long>(model.sensors.size()))
    throw InvalidInput(fmt::format("{} temperatures for the spindle drift model's {} sensors", temperatures.size(), model.sensors.size()));
  Vec6 out = Vec6::Zero();
  for (int d = 0; d < 5; ++d)
    if (model.directions[d]) out[d] = evaluate(*model.directions[d]);
  return out;
}

}  // namespace

Vec6 spindleDrift(const SpindleDriftModel& model, const Eigen::VectorXd& temperatures) {
  return perDirection(model, temperatures, [&](const DriftModel& m) { return m.predict(temperatures); });
}

Vec6 spindleDriftUncertainty(const SpindleDriftModel& model, const Eigen::VectorXd& temperatures) {
  return perDirection(model, temperatures, [&](const DriftModel& m) { return m.predictionUncertainty(temperatures); });
}

}  // namespace mtacc
