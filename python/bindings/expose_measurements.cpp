// Machine: measurement runs simulated and read, the ballbar and R-test evaluations, the
// standard circles of the report, observability and identification, and the hole plates.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/identified_errors.hpp"
#include "mtacc/workflows/measurement_runs.hpp"
#include "mtacc/workflows/simulation_options.hpp"
#include "mtacc/workflows/artefacts.hpp"
#include "mtacc/workflows/plates.hpp"
#include "mtacc/workflows/report_paths.hpp"

namespace mtacc::python {

void exposeMeasurements(MachineBinding& machine) {
  machine
      .def("simulate", [](const PythonMachine& s, const OptionValues& options) { return toPython(toJson(simulatePlanRuns(s, options))); })
      .def("simulate_ballbar", [](const PythonMachine& s, const OptionValues& options) { return toPython(toJson(simulateBallbar(s, options))); })
      .def("simulate_rtest", [](const PythonMachine& s, const OptionValues& options) { return toPython(toJson(simulateRTest(s, options))); })
      .def("read_measurement", [](const PythonMachine& s, const std::string& path) { return toPython(runJson(*s.machine, readMeasurementFile(s, path))); })
      .def("evaluate_ballbar", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(evaluateBallbarFile(s, *OptionReader(evaluationSchema(), options).text("data"))));
      })
      .def("evaluate_rtest", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(evaluateRTestFile(s, *OptionReader(evaluationSchema(), options).text("data"))));
      })
      .def("xy_circle", [](const PythonMachine& s) {
        const auto r = xyCircleTest(s);
        return r ? toPython(toJson(*r)) : py::none().cast<py::object>();
      })
      .def("tilted_circle", [](const PythonMachine& s) {
        const auto r = tiltedCircleTest(s);
        return r ? toPython(toJson(*r)) : py::none().cast<py::object>();
      })
      .def("observability", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(planObservability(s, identificationRequest(observabilitySchema(), options))));
      })
      .def("identify", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const IdentificationRequest request = identificationRequest(identificationSchema(), options);
        IdentificationStudy out;
        {
          py::gil_scoped_release release;
          out = identifyParameters(s, request);
        }
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, out, "errors_out");
        return toPython(toJson(out));
      })
      .def("identify_plates", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const PlateIdentificationRequest request = plateIdentificationRequest(options);
        PlateIdentificationStudy study;
        {
          py::gil_scoped_release release;
          study = identifyPlateFiles(s, request.files, request.pieceLength);
        }
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, *study.machine, study.identified, identificationRecord(study), "errors_out");
        return toPython(toJson(study));
      })
      .def("compare_plate", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(comparePlateFile(s, *OptionReader(plateComparisonSchema(), options).text("data"))));
      })
      .def("simulate_plate", [](const PythonMachine& s, const OptionValues& options) { simulatePlateFile(s, plateSimulationRequest(options)); })
      .def("evaluate_artefact", [](const PythonMachine& s, const OptionValues& options) {
        const std::string data = *OptionReader(artefactEvaluationSchema(), options).text("data");
        ArtefactEvaluation e;
        {
          py::gil_scoped_release release;
          e = evaluateArtefactFile(s, data);
        }
        return toPython(toJson(e));
      })
      .def("simulate_artefact", [](const PythonMachine& s, const OptionValues& options) { simulateArtefactFile(s, artefactSimulationRequest(options)); });
}

}  // namespace mtacc::python
