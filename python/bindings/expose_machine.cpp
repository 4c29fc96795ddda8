// Machine: its check, its errors by name, and the option schemas of every workflow.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/check.hpp"
#include "mtacc/workflows/option_schemas.hpp"

namespace mtacc::python {

void exposeOptions(py::module_& mod) {
  mod.def("option_keys", [](const std::string& workflow) {
    const auto& schemas = workflowOptionSchemas();
    const auto it = schemas.find(workflow);
    if (it == schemas.end()) throw InputError({"", 0, "workflow"}, "no option schema for '" + workflow + "'");
    return it->second->keys();
  }, py::arg("workflow"));
  mod.def("option_schema_workflows", [] {
    std::vector<std::string> names;
    for (const auto& [name, schema] : workflowOptionSchemas()) names.push_back(name);
    return names;
  });
}

void exposeMachineErrors(MachineClass& machine) {
  machine.def("check", [](const PythonMachine& s) { return toPython(toJson(checkMachine(s))); })
      .def("error_unit", [](const PythonMachine& s, const std::string& name) {
        return errorDimension(s, name) == Dimension::Length ? "mm" : "rad";
      })
      .def("get_error", [](const PythonMachine& s, const std::string& name) { return errorValue(s, name); })
      .def("set_error", [](PythonMachine& s, const std::string& name, const py::object& value) {
        setErrorValue(s, name, [&](Dimension d) { return quantity(value, d, name); });
        s.models.reset();
      })
      .def("nonzero_errors", [](const PythonMachine& s) {
        py::dict d;
        for (const auto& [name, value] : nonzeroErrorValues(s)) d[py::str(name)] = value;
        return d;
      });
}

}  // namespace mtacc::python
