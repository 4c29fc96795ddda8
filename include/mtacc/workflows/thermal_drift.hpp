#pragma once
// `mtacc drift`: a thermal drift test (ISO 230-3, seed 003 §2.6) evaluated whole: the mandrel's
// drift per direction with its extremes, the warm-up / cool-down hysteresis against one
// temperature, and per direction the regression of the drift on the temperatures (and on an
// axis's position, where the drift was read at several) with the stepwise choice of a minimal
// sensor set (seed 003 L1026-1050). The test is named from what the file records: the spindle
// running, an axis moving, or neither with the spindle at rest (the environmental temperature
// variation test, whose drift range is its ETVE).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/drift_test_csv.hpp"
#include "mtacc/thermal/drift_regression.hpp"
#include "mtacc/thermal/drift_test.hpp"
#include "mtacc/thermal/spindle_drift.hpp"

namespace mtacc {

struct DriftTestRequest {
  std::string file;
  std::string hysteresisSensor;  // empty: the sensor whose temperature changes most
  SensorSelectionOptions selection;
  std::string positionAxis;      // the axis whose position the drift depends on; empty: the one that moves, if one does
  std::string saveModel;         // where to write the spindle drift model (spindleDriftModel); empty: nowhere
};

// The options of `drift`, declared once (core/option_schema.hpp), and the request they describe.
const OptionSchema& driftTestSchema();
DriftTestRequest driftTestRequest(const OptionValues& values);

enum class DriftTestKind { Spindle, AxisMotion, EnvironmentalVariation, Unstated };
const char* nameOf(DriftTestKind kind);

struct DirectionEvaluation {
  DriftDirection direction = DriftDirection::X;
  DriftExtremes extremes;
  std::optional<DriftHysteresis> hysteresis;
  std::optional<SensorSelection> model;  // absent without temperatures
};

struct DriftTestEvaluation {
  DriftTestFile test;
  MandrelDrift drift;
  DriftTestKind kind = DriftTestKind::Unstated;
  int hysteresisSensor = -1;  // -1 without temperatures
  int positionAxis = -1;      // of test.axes; -1: the drift taken as independent of the position
  std::vector<DirectionEvaluation> directions;  // those the probes give, in X Y Z A B order
};

// Throws InputError naming the file (and the line and column of a bad reading), `sensor` for a
// sensor the file does not hold, `position` for an axis it does not hold or that does not move,
// or for two moving axes and none chosen, or the file's header for too few samples for the sensors;
// with saveModel, also as spindleDriftModel does or for a file that cannot be written (written whole or not at all).
DriftTestEvaluation evaluateDriftTest(const DriftTestRequest& request);
// The test's models as the spindle's drift (each direction's chosen sensors, named), for a
// thermal state's `spindle:`. Throws InputError (key save-model) for a test without
// temperatures or whose models depend on an axis's position.
SpindleDriftModel spindleDriftModel(const DriftTestEvaluation& evaluation);
// Lengths in um, tilts in urad, coefficients per K (and per K per mm), times in s. With seriesPoints > 0 also the
// curves ("series"): time, temperatures, and per direction the drift, the model's prediction and
// its uncertainty (one standard deviation of a new reading, "predicted_sigma"), every k-th
// sample, k chosen for at most seriesPoints.
nlohmann::json toJson(const DriftTestEvaluation& evaluation, size_t seriesPoints = 0);

}  // namespace mtacc
