// Machine: the error budget over the working volume, the sensitivity of the TCP to one error,
// the finite-stiffness summary, the ISO 10791-6 rotary-axis tests and the acceptance tests.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/acceptance.hpp"
#include "mtacc/workflows/budget.hpp"
#include "mtacc/workflows/measurement_design.hpp"
#include "mtacc/workflows/rotary_axis_tests.hpp"
#include "mtacc/workflows/stiffness.hpp"

namespace mtacc::python {

void exposeBudget(MachineBinding& machine) {
  machine
      .def("sensitivity_coefficient", [](const PythonMachine& s, const Array& q, const std::string& name, const py::object& epsilon,
                                         const std::vector<double>& direction) {
        const auto pose = joints(*s.machine, q);
        const std::vector<double> first(pose.row(0).data(), pose.row(0).data() + pose.cols());
        return sensitivityCoefficientAt(s, first, name, quantity(epsilon, errorDimension(s, name), "epsilon"), vec3(direction, "direction"));
      })
      .def("working_volume_grid", [](const PythonMachine& s, int samples) {
        return jointArray(*s.machine, workingVolumeGrid(s, samples));
      })
      .def("budget", [](const PythonMachine& s, const OptionValues& options) {
        const BudgetOptions o = budgetOptions(options);
        BudgetResult r;
        {
          py::gil_scoped_release release;
          r = errorBudget(s, o);
        }
        return toPython(toJson(r));
      })
      .def("sensitivity", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(sensitivities(s, sensitivityRequest(s, options))));
      })
      .def("stiffness", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(summariseStiffness(s, stiffnessSamples(options))));
      })
      .def("acceptance", [](const PythonMachine& s, const OptionValues& options) {
        const std::string tests = *OptionReader(acceptanceSchema(), options).text("tests");
        return toPython(toJson(runAcceptance(s, tests)));
      })
      .def("rotary_tests", [](const PythonMachine& s, const OptionValues& options) {
        const RotaryTestsRequest request = rotaryTestsRequest(options);
        RotaryTestsResult r;
        {
          py::gil_scoped_release release;
          r = rotaryTestsFor(s, request);
        }
        return toPython(toJson(r));
      })
      .def("design", [](const PythonMachine& s, const OptionValues& options) {
        const MeasurementDesignRequest request = measurementDesignRequest(options);
        MeasurementDesign d;
        {
          py::gil_scoped_release release;
          d = designMeasurement(s, request);
        }
        return toPython(toJson(d));
      });
}

}  // namespace mtacc::python
