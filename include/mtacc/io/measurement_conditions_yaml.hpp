#pragma once
// Reading a test's measurement conditions: the instrument and the environment whose uncertainties
// enter the result's (docs/file-formats.md "Measurement conditions").
#include <string>

#include "mtacc/procedures/measurement_uncertainty.hpp"

namespace mtacc {

// Keys not given keep MeasurementConditions' defaults and are listed in `defaulted`. Throws
// InputError naming file, line and key.
MeasurementConditions loadMeasurementConditions(const std::string& path);
MeasurementConditions parseMeasurementConditions(const std::string& yamlText, const std::string& sourceName);
// The defaults of an instrument type alone, every key that applies to it listed as defaulted.
MeasurementConditions defaultMeasurementConditions(InstrumentType type);

}  // namespace mtacc
