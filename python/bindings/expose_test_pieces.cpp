// Machine: the test pieces — the cone frustum, the cubic machining test with its machined
// surface, and the errors identified from the cubic test's zone results.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/cubic_identification.hpp"
#include "mtacc/workflows/identified_errors.hpp"
#include "mtacc/workflows/test_piece_files.hpp"

namespace mtacc::python {
namespace {

// A height map as a (ny, nx) float32 array, row j at y(j), scaled (e.g. mm -> um).
py::array_t<float> heightArray(const HeightMap& m, double scale) {
  py::array_t<float> out({static_cast<py::ssize_t>(m.grid.ny), static_cast<py::ssize_t>(m.grid.nx)});
  float* w = out.mutable_data();
  for (size_t k = 0; k < m.height.size(); ++k) w[k] = static_cast<float>(m.height[k] * scale);
  return out;
}

py::dict gridOf(const HeightGrid& g) { return py::dict(py::arg("x0") = g.x0, py::arg("y0") = g.y0, py::arg("spacing") = g.spacing); }

}  // namespace

void exposeTestPieces(MachineBinding& machine) {
  machine
      .def("cone", [](const PythonMachine& s, const OptionValues& options, const std::string& limitsYaml) {
        ConeStudyRequest request = coneStudyRequest(*s.machine, options);
        request.limitsYaml = limitsYaml;
        ConeStudy r;
        {
          py::gil_scoped_release release;
          r = coneStudy(s, request);
        }
        writeConeFiles(r, coneFiles(options));
        return toPython(toJson(r));
      })
      .def("cone_preset_name", [](const PythonMachine& s) { return conePresetName(*s.machine); })
      .def("cubic", [](const PythonMachine& s, const OptionValues& options) {
        const CubicTestFiles files = cubicTestFiles(options);
        checkCubicTestFiles(files);
        const CubicTestRequest o = cubicTestRequest(options);
        CubicTestStudy r;
        {
          py::gil_scoped_release release;
          r = cubicTestStudy(s, o);
        }
        writeCubicTestFiles(r, files);
        py::dict out = toPython(toJson(r));
        out["grid"] = gridOf(r.actual.grid);
        out["heights_um"] = heightArray(r.actual, 1e3);
        out["referenced_deviation_um"] = heightArray(referencedDeviation(r), 1e3);
        py::list paths;
        for (const auto& z : r.path) paths.append(toArray(z.tips));
        out["tool_tips"] = paths;
        if (!r.sensitivities.empty()) {
          out["sensitivity_grid"] = gridOf(r.sensitivities.front().mapWithAlignment.grid);
          py::dict maps;
          for (const auto& k : r.sensitivities)
            maps[py::str(k.name)] = py::dict(py::arg("with_alignment") = heightArray(k.mapWithAlignment, 1.0),
                                             py::arg("on_table") = heightArray(k.mapOnTable, 1.0));
          out["sensitivity_maps"] = maps;
        }
        return out;
      })
      .def("cubic_identify", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const CubicIdentificationRequest request = cubicIdentificationRequest(options);
        IdentificationStudy out;
        {
          py::gil_scoped_release release;
          out = identifyFromZones(s, request);
        }
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, out, "errors_out");
        return toPython(toJson(out));
      });
}

}  // namespace mtacc::python
