// Machine: seed 003's direct measurements of one component error, simulated and fitted; module
// functions: seed 003's App. B procedures (squareness, yry) and seed 002's closed-form
// identification of a multi-tasking machine from six ball-bar runs.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/direct_procedures.hpp"
#include "mtacc/workflows/multitasking_identification.hpp"
#include "mtacc/workflows/identified_errors.hpp"

namespace mtacc::python {

void exposeProcedures(py::module_& mod) {
  mod.def("squareness", [](const OptionValues& options) { return toPython(toJson(squarenessFromOptions(options))); });
  mod.def("yry", [](const OptionValues& options) { return toPython(toJson(yryFromOptions(options))); });
  mod.def("multitasking", [](const OptionValues& options, const std::string& errorsOut) {
    return toPython(toJson(identifyMultitasking(options, errorsOut)));
  });
}

void exposeDirectMeasurements(MachineBinding& machine) {
  machine
      .def("fit_component", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const ComponentFitRequest r = componentFitRequest(options);
        const auto study = fitComponentFile(s, r);
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, *study.machine, study.errors, identificationRecord(study), "errors_out");
        return toPython(toJson(study));
      })
      .def("simulate_component", [](const PythonMachine& s, const OptionValues& options) {
        simulateComponentFile(s, componentSimulationRequest(options));
      });
}

}  // namespace mtacc::python
