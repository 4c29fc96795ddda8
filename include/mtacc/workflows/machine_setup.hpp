#pragma once
// What every machine workflow starts from: a machine description and its errors, loaded from
// the machine file (a path or a bundled name), an optional errors file, an optional
// workpiece alignment, an optional workpiece load and an optional thermal state. The JSON helpers write poses and vectors the same way in every result.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/input_error.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/io/identification_record.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct MachineSource {
  std::string machine;     // file, or the name of a bundled machine
  std::string errorsFile;  // empty: the machine file's own `errors:`
  std::string alignment;   // "table", "machine", or empty for the machine file's choice
  std::optional<double> load;  // workpiece load (kg), in place of the errors' `workpiece_load`
  std::string thermalFile;     // a thermal state (docs/file-formats.md "Thermal states"); empty: cold (20 degC)
};

struct MachineSetup {
  std::shared_ptr<const Machine> machine;
  ErrorModel errors;
  // What an identified errors file keeps of its estimates' covariance (docs/file-formats.md,
  // "Identified errors"); absent for errors that no identification wrote.
  std::optional<ParameterCovariance> covariance;

  KinematicModel nominal() const { return compileNominal(machine); }
  KinematicModel actual() const { return compile(machine, errors); }
};

// Throws InputError naming file, line and key.
MachineSetup loadMachineSetup(const MachineSource& source);

// Looks each name up (ISO name or alias); throws InputError at `namedAt` (the option or the
// file, line and key that named them) listing the machine's parameters.
std::vector<Parameter> findParameters(const MachineSetup& setup, const std::vector<std::string>& names,
                                      const InputLocation& namedAt = {"", 0, "parameters"});
// A test plan's parameters: the component terms `shape` does not define added to it at zero
// (defineNamedTerms; `names` becomes the expanded list), then looked up in it; an unknown name's
// message also gives the term forms a plan may use.
std::vector<Parameter> findPlanParameters(const std::shared_ptr<const Machine>& machine, ErrorModel& shape,
                                          std::vector<std::string>& names, const InputLocation& namedAt);

// A pose as the front ends take it, "X=10,B=-15" (mm, deg), in the set-up's commanded axes (mm,
// rad): io/pose_text.hpp's reading. partial: the axes not named are zero. Throws InputError naming `key`.
std::vector<double> poseFromText(const MachineSetup& setup, const std::string& text, const std::string& key, bool partial = false);

// One error of the set-up by its ISO 230-1 name or alias (errors/aliases.hpp), in the ISO sign
// convention, mm or rad. setErrorValue defines a component term the errors do not have yet
// (defineParameter) and takes its value from `value` given the term's dimension (a front end's
// reading of a number or a quantity with its unit); nothing changes when it throws.
double errorValue(const MachineSetup& setup, const std::string& name);
Dimension errorDimension(const MachineSetup& setup, const std::string& name);
void setErrorValue(MachineSetup& setup, const std::string& name, const std::function<double(Dimension)>& value);
// Every error whose value is not zero, by parameter name, in the model's own sign (mm or rad).
std::vector<std::pair<std::string, double>> nonzeroErrorValues(const MachineSetup& setup);

// {"X": 10.0, "B": -15.0}: mm for linear and deg for rotary axes, to 15 significant digits.
nlohmann::json poseJson(const Machine& machine, const double* q);
nlohmann::json vectorJson(const Vec3& v);

}  // namespace mtacc
