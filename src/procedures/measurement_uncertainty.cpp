#include "mtacc/procedures/measurement_uncertainty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/procedures/air_refractive_index.hpp"

namespace mtacc {
namespace {

const double kSqrt3 = std::sqrt(3.0);

// The results a contributor enters: the ranges over the targets (A, E, M) compare readings far
// apart, the reversal compares the two directions at one target, the repeatability the cycles.
const std::vector<std::string> kRanges{"A", "A_forward", "A_backward", "E", "E_forward", "E_backward", "M"};
const std::vector<std::string> kReversal{"B"};
const std::vector<std::string> kRepeatability{"R", "R_forward", "R_backward"};

std::vector<std::string> joined(std::initializer_list<const std::vector<std::string>*> groups) {
  std::vector<std::string> out;
  for (const auto* g : groups) out.insert(out.end(), g->begin(), g->end());
  return out;
}

bool isDefaulted(const MeasurementConditions& c, std::initializer_list<const char*> keys) {
  return std::any_of(keys.begin(), keys.end(), [&](const char* k) {
    return std::find(c.defaulted.begin(), c.defaulted.end(), k) != c.defaulted.end();
  });
}

std::string um(double mm) { return fmt::format("{:.3g} um", mm / kMicro); }

}  // namespace

const QuantityUncertainty& UncertaintyBudget::at(const std::string& quantity) const {
  for (const auto& q : quantities)
    if (q.quantity == quantity) return q;
  throw std::out_of_range("no uncertainty of " + quantity);
}

UncertaintyBudget positioningUncertainty(const PositioningTest& test, const PositioningResult& result,
                                         const MeasurementConditions& c) {
  const bool rotary = test.axis == PositioningAxis::Rotary;
  if (rotary != (c.type == InstrumentType::Angle))
    throw InvalidInput(rotary ? "a rotary axis is measured with an angular instrument (type: angle)"
                              : "a linear axis is measured with a length instrument (type: laser or scale)");
  UncertaintyBudget b;
  const double L = test.targets.back() - test.targets.front();
  b.measuredLength = L;
  const auto all = joined({&kRanges, &kReversal, &kRepeatability});
  auto add = [&](std::string symbol, std::string source, double standard, std::initializer_list<const char*> keys,
                 std::vector<std::string> quantities) {
    b.contributors.push_back({std::move(symbol), std::move(source), standard, isDefaulted(c, keys), std::move(quantities)});
  };
  if (rotary) {
    add("u_DEVICE", fmt::format("instrument calibration U = {:.3g} arcsec (k = 2)", c.calibrationConstant / kArcsec),
        c.calibrationConstant / 2, {"calibration"}, joined({&kRanges, &kReversal}));
  } else {
    add("u_DEVICE", fmt::format("instrument calibration U = {:.3g} ppm of {:g} mm (k = 2)", c.calibrationRelative * 1e6, L),
        c.calibrationRelative * L / 2, {"calibration"}, kRanges);
    add("u_DEVICE,0", fmt::format("instrument calibration U = {} (k = 2), constant part", um(c.calibrationConstant)),
        c.calibrationConstant / 2, {"calibration"}, joined({&kRanges, &kReversal}));
  }
  if (c.type == InstrumentType::Laser) {
    const AirConditions air{c.airTemperature.value, c.airPressure.value, c.airHumidity.value};
    const auto dn = airRefractiveIndexSensitivities(air, c.wavelengthNm);
    add("u_λ,T", fmt::format("air temperature sensor ±{:g} K, {:.3g} ppm/K", c.airTemperature.halfWidth, dn.perKelvin * 1e6),
        std::abs(dn.perKelvin) * c.airTemperature.halfWidth / kSqrt3 * L, {"air_temperature"}, kRanges);
    add("u_λ,p", fmt::format("air pressure sensor ±{:g} hPa, {:.3g} ppm/hPa", c.airPressure.halfWidth / 100, dn.perPascal * 1e8),
        std::abs(dn.perPascal) * c.airPressure.halfWidth / kSqrt3 * L, {"air_pressure"}, kRanges);
    add("u_λ,RH", fmt::format("air humidity sensor ±{:g} %, {:.3g} ppm/%", c.airHumidity.halfWidth, dn.perPercent * 1e6),
        std::abs(dn.perPercent) * c.airHumidity.halfWidth / kSqrt3 * L, {"air_humidity"}, kRanges);
    const double deadPathChange = std::hypot(dn.perKelvin * c.airTemperatureChange, dn.perPascal * c.airPressureChange);
    add("u_DEADPATH", fmt::format("dead path {:g} mm, air change {:g} K and {:g} hPa during the test", c.deadPath, c.airTemperatureChange,
                                  c.airPressureChange / 100),
        c.deadPath * deadPathChange / kSqrt3, {"dead_path", "air_change"}, all);
  }
  if (!rotary) {
    add("u_M,MACHINE", fmt::format("machine temperature sensor ±{:g} K, expansion {:.3g} ppm/K", c.machineTemperature.halfWidth,
                                   c.expansion.value * 1e6),
        c.expansion.value * c.machineTemperature.halfWidth / kSqrt3 * L, {"machine_temperature", "expansion"}, kRanges);
    add("u_E,MACHINE", fmt::format("expansion coefficient ±{:.3g} ppm/K at {:g} C (|T - 20 C| = {:g} K)", c.expansion.halfWidth * 1e6,
                                   c.machineTemperature.value, std::abs(c.machineTemperature.value - 20)),
        c.expansion.halfWidth * std::abs(c.machineTemperature.value - 20) / kSqrt3 * L, {"machine_temperature", "expansion"},
        kRanges);
    add("u_MISALIGNMENT", fmt::format("cosine error of a {:g} mm lateral offset over {:g} mm", c.misalignment, L),
        L > 0 ? c.misalignment * c.misalignment / (2 * L) / kSqrt3 : 0.0, {"misalignment"}, kRanges);
  }
  add("u_EVE", fmt::format("environmental variation error E_VE = {} (drift test)",
                           rotary ? fmt::format("{:.3g} arcsec", c.drift / kArcsec) : um(c.drift)),
      c.drift / kSqrt3, {"drift"}, all);

  const double n = result.cycles;
  double s = 0;
  for (const auto& p : result.positions) s = std::max({s, p.sForward, p.sBackward});
  const auto statistical = [&](const std::string& q, double value) {
    if (q[0] == 'A') return s * std::sqrt(2 / n + 4 / (n - 1));
    if (q[0] == 'E' || q == "B") return s * std::sqrt(2 / n);
    if (q == "M") return s / std::sqrt(n);
    return value / std::sqrt(2 * (n - 1));  // R: the spread of an estimated standard deviation
  };
  const std::vector<std::pair<std::string, double>> values{
      {"A", result.accuracy},           {"A_forward", result.accuracyForward},         {"A_backward", result.accuracyBackward},
      {"B", result.reversal},           {"E", result.systematic},                      {"E_forward", result.systematicForward},
      {"E_backward", result.systematicBackward}, {"M", result.meanDeviationRange},    {"R", result.repeatability},
      {"R_forward", result.repeatabilityForward}, {"R_backward", result.repeatabilityBackward}};
  for (const auto& [q, value] : values) {
    const double fromCycles = statistical(q, value);
    double variance = fromCycles * fromCycles;
    for (const auto& k : b.contributors)
      if (std::find(k.quantities.begin(), k.quantities.end(), q) != k.quantities.end()) variance += k.standard * k.standard;
    b.quantities.push_back({q, value, fromCycles, std::sqrt(variance), 2 * std::sqrt(variance)});
  }
  return b;
}

UncertaintyBudget rangeUncertainty(const std::vector<std::pair<std::string, double>>& values, double measuredLength,
                                   const RangeReadings& r) {
  UncertaintyBudget b;
  b.measuredLength = measuredLength;
  std::vector<std::string> all;
  for (const auto& v : values) all.push_back(v.first);
  const double root2 = std::sqrt(2.0);
  b.contributors.push_back({"u_DEVICE", fmt::format("{}: u = {:.3g} {} per reading, twice in a range", r.instrument,
                                                    r.instrumentStandard * r.unitScale, r.unit),
                            root2 * r.instrumentStandard, r.instrumentDefaulted, all});
  if (r.environmentalVariation)
    b.contributors.push_back({"u_EVE", fmt::format("environmental variation error E_VE = {:.3g} {} (drift test)", r.drift * r.unitScale, r.unit),
                              r.drift / kSqrt3, r.driftDefaulted, all});
  if (r.readingsPerMean > 1)
    b.contributors.push_back({"u_REPEAT", fmt::format("scatter s = {:.3g} {} of one reading, means of {}", r.scatter * r.unitScale, r.unit,
                                                      r.readingsPerMean),
                              root2 * r.scatter / std::sqrt(static_cast<double>(r.readingsPerMean)), false, all});
  double variance = 0;
  for (const auto& k : b.contributors) variance += k.standard * k.standard;
  for (const auto& [q, value] : values) b.quantities.push_back({q, value, 0.0, std::sqrt(variance), 2 * std::sqrt(variance)});
  return b;
}

}  // namespace mtacc
