#pragma once
// The Python module's Machine: a machine with its errors, and the conversions at the Python
// boundary (mm and degrees for axis positions).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/error_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/machine/machine_yaml.hpp"

namespace mtacc::python {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

class PyMachine {
 public:
  PyMachine(const std::string& pathOrName, const std::string& errorsFile)
      : machine_(std::make_shared<const Machine>(loadMachine(pathOrName))),
        errors_(errorsFile.empty() ? loadMachineErrors(*machine_) : loadErrors(*machine_, errorsFile)) {}

  const Machine& machine() const { return *machine_; }
  std::shared_ptr<const Machine> shared() const { return machine_; }
  ErrorModel& errors() { return errors_; }

  int axisCount() const { return machine_->commandedCount(); }

  // (n, axes) in mm / deg -> joint matrix in mm / rad.
  JointMatrix joints(const Array& q) const {
    const auto r = q.unchecked<2>();
    if (r.shape(1) != axisCount())
      throw InputError(InputLocation{"", 0, "q"}, "expected " + std::to_string(axisCount()) + " columns (one per axis), got " +
                                                     std::to_string(r.shape(1)));
    JointMatrix out(r.shape(0), r.shape(1));
    for (py::ssize_t i = 0; i < r.shape(0); ++i)
      for (py::ssize_t k = 0; k < r.shape(1); ++k) {
        const double v = r(i, k);
        if (!std::isfinite(v)) throw InputError(InputLocation{"", 0, "q"}, "row " + std::to_string(i) + ": not a finite number");
        out(i, k) = machine_->axes[static_cast<size_t>(k)].isRotary() ? v * kDeg : v;
      }
    return out;
  }

  Eigen::MatrixXi directions(const py::object& dirs, long rows) const {
    if (dirs.is_none()) return {};
    const auto a = py::array_t<int, py::array::c_style | py::array::forcecast>(dirs);
    const auto r = a.unchecked<2>();
    if (r.shape(0) != rows || r.shape(1) != axisCount())
      throw InputError(InputLocation{"", 0, "directions"}, "expected the shape of q");
    Eigen::MatrixXi out(rows, axisCount());
    for (py::ssize_t i = 0; i < rows; ++i)
      for (py::ssize_t k = 0; k < axisCount(); ++k) out(i, k) = r(i, k);
    return out;
  }

  void checkTravel(const JointMatrix& q) const {
    for (long r = 0; r < q.rows(); ++r) {
      const std::vector<double> row(q.row(r).data(), q.row(r).data() + q.cols());
      const auto v = machine_->travelViolation(row);
      if (!v.empty()) throw InputError(InputLocation{"", 0, "row " + std::to_string(r)}, "pose " + v);
    }
  }

 private:
  std::shared_ptr<const Machine> machine_;
  ErrorModel errors_;
};


// Adds simulate, evaluate_ballbar, identify and observability to the Machine class.
void bindMeasurement(py::class_<PyMachine>& cls);
// Adds the Structure class (rigid-body dynamics).
void bindDynamics(py::module_& mod);

}  // namespace mtacc::python
