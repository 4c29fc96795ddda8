// mtacc.Structure: the rigid-body structural dynamics of a structure model. Axis positions in
// mm, FRF and compliances in um/N, acceleration responses in um/g_n, frequencies in Hz.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "py_machine.hpp"

namespace mtacc::python {
namespace {

std::vector<double> axisPositions(const StructureModel& m, const py::dict& at) {
  std::vector<double> q(m.axes.size(), 0.0);
  for (const auto& item : at) {
    const auto name = item.first.cast<std::string>();
    const int j = m.axisIndex(name);
    if (j < 0) throw InputError(InputLocation{m.sourceFile, 0, name}, "no axis '" + name + "' in " + m.name);
    q[static_cast<size_t>(j)] = item.second.cast<double>() * 1e-3;
  }
  return q;
}

py::array_t<double> matrix(const Eigen::MatrixXd& a, double scale) {
  py::array_t<double> out({a.rows(), a.cols()});
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index k = 0; k < a.cols(); ++k) w(i, k) = a(i, k) * scale;
  return out;
}

}  // namespace

void bindDynamics(py::module_& mod) {
  py::class_<StructureModel>(mod, "Structure")
      .def(py::init([](const std::string& pathOrName) { return loadStructure(pathOrName); }), py::arg("model"))
      .def_readonly("name", &StructureModel::name)
      .def_property_readonly("axes", [](const StructureModel& m) {
        py::list out;
        for (const auto& a : m.axes)
          out.append(py::dict(py::arg("name") = a.name, py::arg("travel_mm") = std::vector<double>{a.min * 1e3, a.max * 1e3}));
        return out;
      })
      .def_property_readonly("bodies", [](const StructureModel& m) {
        py::list out;
        for (size_t i = 0; i < m.bodies.size(); ++i) {
          const auto& b = m.bodies[i];
          std::vector<std::string> movedBy;
          for (const auto& a : m.axes)
            if (std::count(a.moves.begin(), a.moves.end(), static_cast<int>(i))) movedBy.push_back(a.name);
          out.append(py::dict(py::arg("name") = b.name, py::arg("mass_kg") = b.mass,
                              py::arg("centre_mm") = std::vector<double>{b.centre.x() * 1e3, b.centre.y() * 1e3, b.centre.z() * 1e3},
                              py::arg("size_mm") = std::vector<double>{b.size.x() * 1e3, b.size.y() * 1e3, b.size.z() * 1e3},
                              py::arg("box_centre_mm") = std::vector<double>{b.boxCentre.x() * 1e3, b.boxCentre.y() * 1e3, b.boxCentre.z() * 1e3},
                              py::arg("moved_by") = movedBy));
        }
        return out;
      })
      .def(
          "modes",
          [](const StructureModel& m, const py::dict& at) {
            const auto mats = assembleStructure(m, axisPositions(m, at));
            const auto modes = undampedModes(m, mats);
            std::vector<double> fd, zeta;
            for (const auto& d : dampedModes(mats)) fd.push_back(d.frequency), zeta.push_back(d.dampingRatio);
            return py::dict(py::arg("frequencies_hz") = std::vector<double>(modes.frequencies.data(), modes.frequencies.data() + modes.frequencies.size()),
                            py::arg("shapes") = matrix(modes.shapes, 1.0), py::arg("damped_frequencies_hz") = fd,
                            py::arg("damping_ratios") = zeta);
          },
          py::arg("at") = py::dict(), "Undamped modes (mass-normalised shapes: 6 per body, m and rad) and damped modes")
      .def(
          "frf",
          [](const StructureModel& m, const std::vector<double>& frequencies, const py::dict& at, const std::string& method) {
            const auto mats = assembleStructure(m, axisPositions(m, at));
            Frf h;
            if (method == "modal") h = frfModal(mats, undampedModes(m, mats), frequencies);
            else if (method == "direct") h = frfDirect(mats, frequencies);
            else throw InputError(InputLocation{"", 0, "method"}, "expected modal or direct");
            py::array_t<std::complex<double>> out({static_cast<py::ssize_t>(h.size()), py::ssize_t{3}, py::ssize_t{3}});
            auto w = out.mutable_unchecked<3>();
            for (size_t s = 0; s < h.size(); ++s)
              for (int i = 0; i < 3; ++i)
                for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(s), i, k) = h[s](i, k) * 1e6;
            return out;
          },
          py::arg("frequencies"), py::arg("at") = py::dict(), py::arg("method") = "modal",
          "3x3 FRF of the TCP relative to the workpiece (um/N, complex), one per frequency (Hz)")
      .def(
          "static_compliance",
          [](const StructureModel& m, const py::dict& at) { return matrix(staticCompliance(assembleStructure(m, axisPositions(m, at))), 1e6); },
          py::arg("at") = py::dict(), "3x3 static compliance, um/N")
      .def(
          "acceleration_response",
          [](const StructureModel& m, const py::dict& at) {
            return matrix(accelerationResponse(assembleStructure(m, axisPositions(m, at))), kStandardGravity * 1e6);
          },
          py::arg("at") = py::dict(), "3 x axes: TCP displacement per axis acceleration, um/g_n (seed 000 Table 7.1 form)")
      .def(
          "map",
          [](const StructureModel& m, const std::string& quantity, const std::vector<std::string>& axes,
             const std::vector<int>& grid, const py::dict& at) {
            if (axes.size() != 2 || grid.size() != 2) throw InputError(InputLocation{"", 0, "axes"}, "expected two axes and two counts");
            const auto q = dynamicsQuantity(m, quantity);
            DynamicsMap r;
            {
              py::gil_scoped_release release;
              r = dynamicsMap(m, axisPositions(m, at), axes[0], axes[1], grid[0], grid[1], q);
            }
            std::vector<double> a, b;
            for (double v : r.a) a.push_back(v * 1e3);
            for (double v : r.b) b.push_back(v * 1e3);
            const auto& s = r.statistics;
            return py::dict(py::arg("quantity") = q.name, py::arg("unit") = q.unit, py::arg("axes") = axes, py::arg("a_mm") = a,
                            py::arg("b_mm") = b, py::arg("values") = matrix(r.values, 1.0),
                            py::arg("statistics") = py::dict(py::arg("min") = s.min, py::arg("lower_quartile") = s.lowerQuartile,
                                                             py::arg("median") = s.median, py::arg("upper_quartile") = s.upperQuartile,
                                                             py::arg("max") = s.max));
          },
          py::arg("quantity") = "Hx/X", py::arg("axes") = std::vector<std::string>{"Y", "Z"},
          py::arg("grid") = std::vector<int>{20, 20}, py::arg("at") = py::dict(),
          "A quantity (Hx/X um/g, Cxx um/N, f1 Hz) over a grid of two axes, with its statistics");
}

}  // namespace mtacc::python
