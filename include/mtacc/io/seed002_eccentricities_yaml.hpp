#pragma once
// The eccentricities of seed 002's six ball-bar runs and their set-up (Table 6's form), the
// input of the closed-form identification of a B-head / C-spindle multi-tasking machine
// (docs/file-formats.md "Multi-tasking ball-bar eccentricities").
#include <string>

#include "mtacc/procedures/ballbar_seed002.hpp"

namespace mtacc {

struct Seed002Measurements {
  std::string file;
  Seed002Eccentricities eccentricities;  // mm
  Seed002Setup setup;                    // mm
  int setupLine = 0;                     // of `setup:`, for messages about it
};

// Throws InputError naming file, line and key.
Seed002Measurements parseSeed002Eccentricities(const std::string& yamlText, const std::string& sourceName);
Seed002Measurements loadSeed002Eccentricities(const std::string& path);

}  // namespace mtacc
