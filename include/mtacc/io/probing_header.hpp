#pragma once
// The header lines that the plate and the artefact measurement files share (docs/file-formats.md
// "Plate measurements", "Artefact measurements"): where the artefact lies, how it was probed,
// at which temperatures, and the 2S values of the residual budget. One reader and one writer
// for both files.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/machine/machine.hpp"
#include "mtacc/measurement/plates.hpp"

namespace mtacc {

struct ProbingHeader {
  Vec3 origin = Vec3::Zero();
  bool originGiven = false;
  int originLine = 0;
  Vec3 u = Vec3::UnitX(), v = Vec3::UnitY();
  Vec3 stylus = Vec3::Zero();
  std::vector<double> pose;  // every commanded axis, mm and rad; empty: the reference pose
  PlateTemperatures temperatures;
  std::vector<double> probe;         // 2S per direction as given, mm
  std::optional<double> simulation;  // 2S of the model's prediction, mm
};

// Reads one "# key: value" line into `header` when `key` is origin, axes, stylus, pose,
// temperatures, expansion, probe or simulation, and returns false for any other key. Throws
// InputError naming the key (without file and line: the caller adds them).
bool readProbingKey(const Machine& machine, const std::string& key, const std::string& value, int line, ProbingHeader& header);
// The same lines as text, each number at full precision.
std::string probingHeaderText(const Machine& machine, const ProbingHeader& header);

}  // namespace mtacc
