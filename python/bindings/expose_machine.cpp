// Machine: its check, its errors by name, and the option schemas of every workflow.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/check.hpp"
#include "mtacc/workflows/option_schemas.hpp"

namespace mtacc::python {

namespace {

const OptionSchema& schemaNamed(const std::string& workflow) {
  const auto& schemas = workflowOptionSchemas();
  const auto it = schemas.find(workflow);
  if (it == schemas.end()) throw InputError({"", 0, "workflow"}, "no option schema for '" + workflow + "'");
  return *it->second;
}

py::object orNone(const auto& value) { return value ? py::cast(*value) : py::none(); }

}  // namespace

void exposeOptions(py::module_& mod) {
  mod.def("option_keys", [](const std::string& workflow) { return schemaNamed(workflow).keys(); }, py::arg("workflow"));
  // Each field as a Python front end builds its arguments from it (the report's command line).
  mod.def("option_fields", [](const std::string& workflow) {
    static const char* kinds[] = {"text", "list", "numbers", "flag", "count", "number", "quantity"};
    py::list out;
    for (const auto& f : schemaNamed(workflow).fields)
      out.append(py::dict(py::arg("key") = f.key, py::arg("kind") = kinds[static_cast<int>(f.kind)], py::arg("help") = optionHelp(f),
                          py::arg("positional") = f.positional, py::arg("required") = f.required));
    return out;
  }, py::arg("workflow"));
  // The values read and checked as the workflow reads them, its defaults filled in (quantities in mm or rad).
  mod.def("read_options", [](const std::string& workflow, const OptionValues& values) {
    const OptionSchema& schema = schemaNamed(workflow);
    const OptionReader read(schema, values);
    py::dict out;
    for (const auto& f : schema.fields) {
      const py::str key(f.key);
      switch (f.kind) {
        case OptionKind::Text: out[key] = orNone(read.text(f.key)); break;
        case OptionKind::List: out[key] = read.list(f.key); break;
        case OptionKind::Numbers: out[key] = read.numbers(f.key); break;
        case OptionKind::Flag: out[key] = read.flag(f.key); break;
        case OptionKind::Count: out[key] = orNone(read.count(f.key)); break;
        case OptionKind::Number: out[key] = orNone(read.number(f.key)); break;
        case OptionKind::Quantity: out[key] = orNone(read.quantity(f.key)); break;
      }
    }
    return out;
  }, py::arg("workflow"), py::arg("values"));
  mod.def("option_schema_workflows", [] {
    std::vector<std::string> names;
    for (const auto& [name, schema] : workflowOptionSchemas()) names.push_back(name);
    return names;
  });
}

void exposeMachineErrors(MachineBinding& machine) {
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
