// Machine: seed 003's direct measurements of one component error, simulated and fitted.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/identified_errors.hpp"

namespace mtacc::python {

void exposeDirectMeasurements(MachineClass& machine) {
  machine
      .def("fit_component", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const ComponentFitRequest r = componentFitRequest(options);
        const auto study = fitComponentFile(s, r);
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, *study.machine, study.errors, identificationRecord(study), "errors_out");
        return toPython(toJson(study));
      })
      .def("simulate_component", [](const PythonMachine& s, const std::string& component, const std::string& output, double step, int runs,
                                    const std::string& noise, const std::vector<double>& abbe, const std::string& disturbance,
                                    double interval, const std::string& settling, double settlingTime, std::uint64_t seed) {
        ComponentSimulationRequest r{.component = component, .output = output, .step = step, .runs = runs, .noise = noise};
        if (abbe.size() != 3) throw InputError(InputLocation{"", 0, "abbe_offset"}, "expected (dx, dy, dz) in mm");
        r.abbeOffset = Vec3(abbe[0], abbe[1], abbe[2]);
        r.disturbance = disturbance;
        r.disturbanceInterval = interval;
        r.settling = settling;
        r.settlingTime = settlingTime;
        r.seed = seed;
        simulateComponentFile(s, r);
      });
}

}  // namespace mtacc::python
