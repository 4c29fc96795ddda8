// Machine: compensated programs, controller tables, and a program's deviation from its intended path.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/compensation.hpp"
#include "mtacc/workflows/program_deviation.hpp"

namespace mtacc::python {

void exposeCompensation(MachineClass& machine) {
  machine
      .def("compensation_tables",
           [](const PythonMachine& s, const std::array<int, 3>& nodes, const std::string& pose, int functions, int linuxcncType,
              const std::string& checkProgram) {
             CompensationTablesRequest request;
             request.checkProgram = checkProgram;
             request.grid.counts = nodes;
             if (!pose.empty()) request.grid.pose = poseFromText(s, pose, "pose", true);
             request.oneAxisFunctions = functions;
             request.linuxcncType = linuxcncType;
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
           [](const PythonMachine& s, const std::string& program, const std::string& intended, const std::map<int, double>& toolLengths,
              double step) {
             ProgramDeviationResult r;
             {
               py::gil_scoped_release release;
               r = programDeviationFile(s, {program, intended, toolLengths, {step}});
             }
             return toPython(toJson(r));
           })
      .def("compensate_program",
           [](const PythonMachine& s, const std::string& path, const std::map<int, double>& toolLengths, std::optional<double> tolerance,
              std::optional<double> directionTolerance, const std::string& checkErrors) {
             ProgramCompensationRequest request;
             request.programFile = path;
             request.toolLengths = toolLengths;
             request.checkErrorsFile = checkErrors;
             if (tolerance) request.options.tolerance = *tolerance;
             if (directionTolerance) request.options.directionTolerance = *directionTolerance;
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
