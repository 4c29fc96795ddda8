#include "mtacc/workflows/machine_setup.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/io/thermal_state_yaml.hpp"

namespace mtacc {

MachineSetup loadMachineSetup(const MachineSource& source) {
  Machine loaded = loadMachine(source.machine);
  if (source.alignment == "table") loaded.alignment = WorkpieceAlignment::Table;
  else if (source.alignment == "machine") loaded.alignment = WorkpieceAlignment::Machine;
  else if (!source.alignment.empty()) throw InputError(InputLocation{"", 0, "alignment"}, "expected 'table' or 'machine'");
  auto machine = std::make_shared<const Machine>(std::move(loaded));
  ErrorModel errors = source.errorsFile.empty() ? loadMachineErrors(*machine) : loadErrors(*machine, source.errorsFile);
  if (source.load) {
    if (!(*source.load >= 0.0 && *source.load <= 1e6))
      throw InputError(InputLocation{"", 0, "load"}, "the workpiece load must lie in 0 to 1e6 kg");
    errors.workpieceLoad = *source.load;
  }
  if (!source.thermalFile.empty()) {
    const auto state = loadThermalState(*machine, source.thermalFile);
    try {
      errors = atThermalState(*machine, std::move(errors), state);
    } catch (const InvalidInput& e) {
      throw InputError(InputLocation{source.thermalFile, 0, "thermal"}, e.what());
    }
  }
  auto covariance = source.errorsFile.empty() ? std::nullopt : readParameterCovariance(*machine, errors, source.errorsFile);
  return {machine, std::move(errors), std::move(covariance)};
}

std::vector<Parameter> findParameters(const MachineSetup& setup, const std::vector<std::string>& names,
                                      const InputLocation& namedAt) {
  std::vector<Parameter> out;
  try {
    for (const auto& n : names) out.push_back(findParameter(*setup.machine, setup.errors, n));
  } catch (const InputError& e) {
    throw InputError(namedAt, e.reason());
  }
  return out;
}

std::vector<Parameter> findPlanParameters(const std::shared_ptr<const Machine>& machine, ErrorModel& shape,
                                          std::vector<std::string>& names, const InputLocation& namedAt) {
  names = defineNamedTerms(*machine, shape, names);
  try {
    return findParameters(MachineSetup{machine, shape, std::nullopt}, names, namedAt);
  } catch (const InputError& e) {
    throw InputError(e.where(), e.reason() +
                                    "; a test plan may also name a component-error term the errors do not define: "
                                    "E<D><axis>.c<k> (power k over the travel, e.g. EXX.c1) or E<D><axis>.h<k> (harmonic "
                                    "of order k, amplitude and phase, e.g. ECC.h1)");
  }
}

std::vector<double> poseFromText(const MachineSetup& setup, const std::string& text, const std::string& key, bool partial) {
  return parsePose(*setup.machine, text, key, partial);
}

double errorValue(const MachineSetup& setup, const std::string& name) {
  return isoSign(name) * parameterValue(setup.errors, findParameter(*setup.machine, setup.errors, name));
}

Dimension errorDimension(const MachineSetup& setup, const std::string& name) {
  return findParameter(*setup.machine, setup.errors, name).dimension;
}

void setErrorValue(MachineSetup& setup, const std::string& name, const std::function<double(Dimension)>& value) {
  ErrorModel errors = setup.errors;
  const Parameter p = defineParameter(*setup.machine, errors, name);
  setParameterValue(errors, p, isoSign(name) * value(p.dimension));
  setup.errors = std::move(errors);
}

std::vector<std::pair<std::string, double>> nonzeroErrorValues(const MachineSetup& setup) {
  std::vector<std::pair<std::string, double>> values;
  for (const auto& p : nonZeroParameters(*setup.machine, setup.errors)) values.emplace_back(p.name, parameterValue(setup.errors, p));
  return values;
}

nlohmann::json poseJson(const Machine& m, const double* q) {
  nlohmann::json j = nlohmann::json::object();
  for (int i = 0; i < m.commandedCount(); ++i) {
    const Axis& a = m.axes[static_cast<size_t>(i)];
    // 15 significant digits: no "29.99999999999999" (rounding of a few ulp) for 30 degrees.
    j[a.name] = std::stod(fmt::format("{:.15g}", a.isRotary() ? q[i] / kDeg : q[i]));
  }
  return j;
}

nlohmann::json vectorJson(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace mtacc
