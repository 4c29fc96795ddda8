#include "mtacc/io/measurement_conditions_yaml.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

const std::vector<std::string> kKeys{"instrument",          "type",      "calibration", "air_temperature", "air_pressure",
                                     "air_humidity",        "air_change", "dead_path",  "wavelength",      "machine_temperature",
                                     "expansion",           "misalignment", "drift"};
const std::vector<std::string> kLaserOnly{"air_temperature", "air_pressure", "air_humidity", "air_change", "dead_path", "wavelength"};
const std::vector<std::string> kLengthOnly{"machine_temperature", "expansion", "misalignment"};

// A unit's factor to the value's internal unit, per kind of value.
using Units = std::map<std::string, double>;
const Units kCelsius{{"C", 1.0}, {"°C", 1.0}};
const Units kKelvin{{"K", 1.0}};
const Units kPressure{{"Pa", 1.0}, {"hPa", 100.0}, {"mbar", 100.0}, {"kPa", 1000.0}};
const Units kPercent{{"%", 1.0}};
const Units kPerKelvin{{"ppm/K", 1e-6}, {"/K", 1.0}, {"1/K", 1.0}};
const Units kNanometre{{"nm", 1.0}};

struct Reader {
  const yamlin::Context& ctx;
  const YAML::Node& root;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const { ctx.fail(root[key], key, what); }

  std::string text(const std::string& key) const { return yamlin::scalar(ctx, root[key], key); }

  // "<number> <unit>" with the unit one of `units`, the value within [low, high].
  double valueIn(const std::string& key, const std::string& item, const Units& units, double low, double high, const char* example) const {
    const auto blank = item.find_first_of(" \t");
    const auto unit = blank == std::string::npos ? std::string{} : trim(item.substr(blank));
    const auto found = units.find(unit);
    if (found == units.end()) {
      std::string names;
      for (const auto& u : units) names += (names.empty() ? "" : ", ") + u.first;
      fail(key, fmt::format("expected a number and one of the units {} in '{}' (e.g. '{}')", names, item, example));
    }
    double v = 0;
    try {
      v = parseNumber(trim(item.substr(0, blank)), key) * found->second;
    } catch (const InputError& e) {
      fail(key, e.reason());
    }
    if (!(v >= low && v <= high))
      fail(key, fmt::format("'{}' is outside {:g} to {:g} {}", item, low / found->second, high / found->second, unit));
    return v;
  }

  // "<reading> <unit> ± <half-width> <unit>" (also "+-").
  BoundedValue bounded(const std::string& key, const Units& valueUnits, double low, double high, const Units& widthUnits,
                       double widest, const char* example) const {
    const std::string t = text(key);
    auto at = t.find("±");
    size_t width = 2;
    if (at == std::string::npos) {
      at = t.find("+-");
      width = 2;
    }
    if (at == std::string::npos) fail(key, fmt::format("expected a reading and its bound, e.g. '{}'", example));
    return {valueIn(key, trim(t.substr(0, at)), valueUnits, low, high, example),
            valueIn(key, trim(t.substr(at + width)), widthUnits, 0, widest, example)};
  }

  double quantity(const std::string& key, Dimension dimension, double largest, const char* largestText, const char* example) const {
    double v = 0;
    try {
      v = parseQuantityAs(text(key), dimension, key);
    } catch (const InputError& e) {
      fail(key, e.reason() + fmt::format(" (e.g. '{}')", example));
    }
    if (!(v >= 0 && v <= largest)) fail(key, fmt::format("expected 0 to {}", largestText));
    return v;
  }
};

// "0.4 ppm + 0.1 um", "0.4 ppm", "0.1 um"; an angle instrument: "1 arcsec".
void readCalibration(const Reader& r, MeasurementConditions& c) {
  const std::string key = "calibration";
  const auto parts = splitList(r.text(key), '+');
  if (parts.empty() || parts.size() > 2) r.fail(key, "expected 'R ppm + C um', 'R ppm' or 'C um' (U, k = 2)");
  c.calibrationRelative = 0;
  c.calibrationConstant = 0;
  bool relative = false, constant = false;
  for (const auto& raw : parts) {
    const auto part = trim(raw);
    if (part.size() > 3 && part.substr(part.size() - 3) == "ppm") {
      if (relative || c.type == InstrumentType::Angle) r.fail(key, "one length-proportional part in ppm, for a length instrument");
      c.calibrationRelative = r.valueIn(key, part, {{"ppm", 1e-6}}, 0, 100e-6, "0.4 ppm + 0.1 um");
      relative = true;
    } else {
      if (constant) r.fail(key, "one constant part");
      const Dimension d = c.type == InstrumentType::Angle ? Dimension::Angle : Dimension::Length;
      try {
        c.calibrationConstant = parseQuantityAs(part, d, key);
      } catch (const InputError& e) {
        r.fail(key, e.reason());
      }
      const double largest = d == Dimension::Length ? 1.0 : 1.0 * kDeg;
      if (!(c.calibrationConstant >= 0 && c.calibrationConstant <= largest))
        r.fail(key, d == Dimension::Length ? "expected 0 to 1 mm" : "expected 0 to 1 deg");
      constant = true;
    }
  }
}

bool applies(InstrumentType type, const std::string& key) {
  const auto in = [&](const std::vector<std::string>& keys) { return std::find(keys.begin(), keys.end(), key) != keys.end(); };
  return !(type != InstrumentType::Laser && in(kLaserOnly)) && !(type == InstrumentType::Angle && in(kLengthOnly));
}

// The defaults of an instrument type: an angular one 1 arcsec (k = 2) and no length contributors.
MeasurementConditions conditionsFor(InstrumentType type) {
  MeasurementConditions c;
  c.type = type;
  if (type == InstrumentType::Scale) c.instrument = "reference scale";
  if (type == InstrumentType::Angle) {
    c.instrument = "angular instrument";
    c.calibrationRelative = 0;
    c.calibrationConstant = 1 * kArcsec;
  }
  return c;
}

}  // namespace

MeasurementConditions defaultMeasurementConditions(InstrumentType type) {
  MeasurementConditions c = conditionsFor(type);
  for (auto key = kKeys.begin() + 2; key != kKeys.end(); ++key)  // instrument and type are names, not values
    if (applies(type, *key)) c.defaulted.push_back(*key);
  return c;
}

MeasurementConditions loadMeasurementConditions(const std::string& path) {
  return parseMeasurementConditions(readTextFile(path), path);
}

MeasurementConditions parseMeasurementConditions(const std::string& yamlText, const std::string& sourceName) {
  const yamlin::Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping of the instrument and environment keys (docs/file-formats.md)");
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end())
      ctx.fail(kv.first, key, "unknown key (instrument, type, calibration, air_temperature, air_pressure, air_humidity, air_change, "
                              "dead_path, wavelength, machine_temperature, expansion, misalignment, drift)");
  }
  const Reader r{ctx, root};
  InstrumentType type = InstrumentType::Laser;
  if (root["type"]) {
    const auto name = r.text("type");
    if (name == "laser") type = InstrumentType::Laser;
    else if (name == "scale") type = InstrumentType::Scale;
    else if (name == "angle") type = InstrumentType::Angle;
    else r.fail("type", "expected laser, scale or angle");
  }
  MeasurementConditions c = conditionsFor(type);
  if (root["type"]) c.typeLine = ctx.at(root["type"], "type").line;
  for (const auto& key : kLaserOnly)
    if (root[key] && type != InstrumentType::Laser) r.fail(key, "applies to a laser interferometer only (type: laser)");
  for (const auto& key : kLengthOnly)
    if (root[key] && type == InstrumentType::Angle) r.fail(key, "applies to a linear axis only (not to type: angle)");
  if (root["instrument"]) c.instrument = r.text("instrument");
  const auto given = [&](const std::string& key) {
    if (root[key]) return true;
    if (applies(type, key)) c.defaulted.push_back(key);
    return false;
  };
  if (given("calibration")) readCalibration(r, c);
  if (given("air_temperature")) c.airTemperature = r.bounded("air_temperature", kCelsius, 0, 40, kKelvin, 10, "20.6 C ± 0.2 K");
  if (given("air_pressure")) c.airPressure = r.bounded("air_pressure", kPressure, 60e3, 120e3, kPressure, 5e3, "1001 hPa ± 1 hPa");
  if (given("air_humidity")) c.airHumidity = r.bounded("air_humidity", kPercent, 0, 100, kPercent, 50, "45 % ± 6 %");
  if (given("air_change")) {
    const auto parts = splitList(r.text("air_change"));
    if (parts.size() != 2) r.fail("air_change", "expected the air's temperature and pressure change during the test, e.g. '0.4 K, 1.5 hPa'");
    c.airTemperatureChange = r.valueIn("air_change", trim(parts[0]), kKelvin, 0, 20, "0.4 K, 1.5 hPa");
    c.airPressureChange = r.valueIn("air_change", trim(parts[1]), kPressure, 0, 5e3, "0.4 K, 1.5 hPa");
  }
  if (given("dead_path")) c.deadPath = r.quantity("dead_path", Dimension::Length, 1e5, "100 m", "120 mm");
  if (given("wavelength")) c.wavelengthNm = r.valueIn("wavelength", r.text("wavelength"), kNanometre, 300, 1700, "632.99 nm");
  if (given("machine_temperature"))
    c.machineTemperature = r.bounded("machine_temperature", kCelsius, -10, 50, kKelvin, 10, "21.4 C ± 0.2 K");
  if (given("expansion")) c.expansion = r.bounded("expansion", kPerKelvin, -50e-6, 50e-6, kPerKelvin, 50e-6, "11.5 ppm/K ± 2 ppm/K");
  if (given("misalignment")) c.misalignment = r.quantity("misalignment", Dimension::Length, 100, "100 mm", "0.5 mm");
  if (given("drift")) {
    const bool angle = c.type == InstrumentType::Angle;
    c.drift = r.quantity("drift", angle ? Dimension::Angle : Dimension::Length, angle ? 1 * kDeg : 1.0, angle ? "1 deg" : "1 mm",
                         angle ? "2 arcsec" : "1.2 um");
  }
  return c;
}

}  // namespace mtacc
