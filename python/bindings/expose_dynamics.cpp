// Structure: the rigid-body model's modes, FRFs, acceleration response and maps; Machine: seed
// 004's virtual machine and the decomposition of recorded TCP errors.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/dynamics_options.hpp"
#include "mtacc/workflows/recorded_decomposition.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

namespace mtacc::python {

void exposeDynamics(py::module_& mod, MachineBinding& machine) {
  machine
      .def("decompose", [](const PythonMachine& s, const OptionValues& options) {
        const DecompositionRequest request = decompositionRequest(options);
        const auto set = loadDecompositionSet(request);
        RecordedDecomposition result;
        {
          py::gil_scoped_release release;
          result = decomposeRecordedSet(s, set);
        }
        return toPython(toJson(result, request.seriesPoints));
      })
      .def("simulate_motion", [](const PythonMachine& s, const OptionValues& options) {
        const MotionSimulationRequest request = motionSimulationRequest(options);
        MotionSimulationResult simulation;
        {
          py::gil_scoped_release release;
          simulation = simulateMotion(s, request);
        }
        return toPython(toJson(simulation));
      });

  py::class_<StructureModel>(mod, "Structure")
      .def(py::init([](const std::string& pathOrName) { return loadStructureModel(pathOrName); }), py::arg("model"))
      .def_readonly("name", &StructureModel::name)
      .def("positions", [](const StructureModel& m, const std::string& at) { return structurePositions(m, at); })
      .def("modes", [](const StructureModel& m, const OptionValues& options) {
        return toPython(toJson(structureModes(m, structurePositionsOf(m, structureModesSchema(), options)), modesCount(options)));
      })
      .def("frf", [](const StructureModel& m, const std::vector<double>& frequencies, const OptionValues& options) {
        FrfRequest request = structureFrfRequest(m, options);
        request.frequencies = frequencies;
        return toPython(toJson(structureFrf(m, request)));
      })
      .def("acceleration_response", [](const StructureModel& m, const OptionValues& options) {
        return toPython(toJson(structureAcceleration(m, structurePositionsOf(m, structureAccelerationSchema(), options))));
      })
      .def("map", [](const StructureModel& m, const OptionValues& options) {
        MapResult r;
        const MapRequest request = structureMapRequest(m, options);
        {
          py::gil_scoped_release release;
          r = structureMap(m, request);
        }
        return toPython(toJson(r));
      })
      .def("describe", [](const StructureModel& m) { return toPython(structureJson(m)); });
}

}  // namespace mtacc::python
