// Machine: compensated programs, controller tables, and a program's deviation from its intended path.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/compensate_options.hpp"
#include "mtacc/workflows/program_deviation.hpp"

namespace mtacc::python {

void exposeCompensation(MachineBinding& machine) {
  machine
      .def("compensation_tables",
           [](const PythonMachine& s, const OptionValues& options) {
             const CompensationTablesRequest request = compensationTablesRequest(s, options);
             CompensationTablesResult r;
             {
               py::gil_scoped_release release;
               r = compensationTables(s, request);
             }
             nlohmann::json j = toJson(r);
             j["contents"] = nlohmann::json::object();
             for (const auto& [name, content] : r.files) j["contents"][name] = content;
             return toPython(j);
           })
      .def("deviation",
           [](const PythonMachine& s, const OptionValues& options) {
             const ProgramDeviationRequest request = programDeviationRequest(options);
             ProgramDeviationResult r;
             {
               py::gil_scoped_release release;
               r = programDeviationFile(s, request);
             }
             return toPython(toJson(r));
           })
      .def("compensate_program",
           [](const PythonMachine& s, const OptionValues& options) {
             const ProgramCompensationRequest request = programCompensationRequest(options);
             ProgramCompensationResult r;
             {
               py::gil_scoped_release release;
               r = compensateProgramFile(s, request);
             }
             nlohmann::json j = toJson(r);
             j["gcode"] = r.gcode;
             return toPython(j);
           });
}

}  // namespace mtacc::python
