// The Python module mtacc._mtacc: each function calls one workflow of the library and returns
// its result as the CLI's --json prints it (converted to Python objects), or as numpy arrays
// for the batch kinematics. Units at this interface are those of the CLI: mm and degrees for
// axis positions, mm for the TCP, um and urad for errors. The bindings are in expose_<family>.cpp.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/version.hpp"
#include "mtacc/workflows/machine_setup.hpp"

using namespace mtacc;
using namespace mtacc::python;

PYBIND11_MODULE(_mtacc, mod) {
  mod.doc() = "mtacc: geometric accuracy of multi-axis machine tools (C++ core)";
  mod.attr("__version__") = version();
  static py::exception<InputError> inputError(mod, "InputError", PyExc_ValueError);
  static py::exception<UnreachablePose> unreachable(mod, "UnreachablePose", inputError.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UnreachableInput& e) {
      unreachable(e.what());
    } catch (const InputError& e) {
      inputError(e.what());
    } catch (const UnreachablePose& e) {
      unreachable((std::string("unreachable pose: ") + e.what()).c_str());
    }
  });

  MachineBinding machine(mod, "Machine");
  machine.def(py::init([](const std::string& path, const std::string& errors, const std::string& alignment, std::optional<double> load,
                          const std::string& thermal) { return PythonMachine{{loadMachineSetup({path, errors, alignment, load, thermal})}, {}}; }),
              py::arg("machine"), py::arg("errors") = "", py::arg("alignment") = "", py::arg("load") = py::none(), py::arg("thermal") = "");
  exposeOptions(mod);
  exposeMachineErrors(machine);
  exposeKinematics(machine);
  exposeBudget(machine);
  exposeTestPieces(machine);
  exposeMeasurements(machine);
  exposeDirectMeasurements(machine);
  exposeProcedures(mod);
  exposeCompensation(machine);
  exposeDynamics(mod, machine);
  exposeThermal(mod);
}
