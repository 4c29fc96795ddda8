#pragma once
// Workflow `multitasking`: the twelve location errors of a multi-tasking machine with a B swivel
// head and a C work spindle from the eccentricities of six ball-bar runs (seed 002 §5, the
// closed forms of Eqs 17-28), optionally written as an errors file of seed 002's names.
#include <nlohmann/json.hpp>

#include <string>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/seed002_eccentricities_yaml.hpp"

namespace mtacc {

struct MultitaskingIdentification {
  Seed002Measurements input;
  Seed002Deviations deviations;  // mm, rad
};

// data: the eccentricities file.
const OptionSchema& multitaskingSchema();
// Reads, identifies and, with `errorsOut`, writes the errors file there atomically. Throws
// InputError naming the file for a set-up that cannot separate the deviations.
MultitaskingIdentification identifyMultitasking(const OptionValues& options, const std::string& errorsOut = "");

// The deviations by seed 002's names (Table 1), um and arcsec, and the ISO names they stand for.
nlohmann::json toJson(const MultitaskingIdentification& identification);
// An errors file (seed 002's names are aliases the errors files read) for a machine of this
// kind, e.g. the bundled multitasking-b-c.
std::string multitaskingErrorsYaml(const MultitaskingIdentification& identification);

}  // namespace mtacc
