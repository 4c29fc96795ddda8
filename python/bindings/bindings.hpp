#pragma once
// Shared by the bindings of mtacc._mtacc (one expose_<family>.cpp each): what they convert: results to Python objects (the CLI's --json) and
// numpy arrays, and numpy arrays and Python numbers to the library's types, each checked and an
// InputError naming the keyword for what is not right.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/units.hpp"
#include "mtacc/workflows/kinematics_batch.hpp"

namespace mtacc::python {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::object toPython(const nlohmann::json& j);

template <class Matrix>
py::array_t<double> toArray(const Matrix& m, double scale = 1.0) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index k = 0; k < m.cols(); ++k) w(i, k) = m(i, k) * scale;
  return out;
}

// (n, axes) in mm / deg -> joint matrix in mm / rad.
JointMatrix joints(const Machine& m, const Array& q);
// A joint matrix (mm / rad) -> (n, axes) in mm / deg.
py::array_t<double> jointArray(const Machine& m, const JointMatrix& q);
// Each pose's direction choice (the shape of q), or none.
DirectionMatrix directions(const py::object& dirs, const JointMatrix& q);
Vec3 vec3(const std::vector<double>& v, const std::string& key);
// A number in mm or rad, or text with its unit ("10 um").
double quantity(const py::object& value, Dimension d, const std::string& key);

// The module's Machine: a setup whose compiled models are kept between calls, so that a pose at
// a time costs an evaluation, not a compilation; set_error drops them.
struct PythonMachine : MachineSetup {
  mutable std::optional<std::pair<KinematicModel, KinematicModel>> models;  // actual, nominal

  const std::pair<KinematicModel, KinematicModel>& compiled() const {
    if (!models) models.emplace(actual(), nominal());
    return *models;
  }
};
using MachineBinding = py::class_<PythonMachine>;

// The bindings by family, each adding its functions to the module or its methods to Machine.
void exposeOptions(py::module_& mod);
void exposeMachineErrors(MachineBinding& machine);
void exposeKinematics(MachineBinding& machine);
void exposeBudget(MachineBinding& machine);
void exposeTestPieces(MachineBinding& machine);
void exposeMeasurements(MachineBinding& machine);
void exposeDirectMeasurements(MachineBinding& machine);
void exposeProcedures(py::module_& mod);
void exposeCompensation(MachineBinding& machine);
void exposeDynamics(py::module_& mod, MachineBinding& machine);
void exposeThermal(py::module_& mod);

}  // namespace mtacc::python
