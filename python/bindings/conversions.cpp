#include <cmath>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"

namespace mtacc::python {

py::object toPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

JointMatrix joints(const Machine& m, const Array& q) {
  if (q.ndim() != 2 || q.shape(1) != m.commandedCount())
    throw InputError(InputLocation{"", 0, "q"}, "expected an (n, " + std::to_string(m.commandedCount()) + ") array, one column per axis");
  const auto r = q.unchecked<2>();
  JointMatrix out(r.shape(0), r.shape(1));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (py::ssize_t k = 0; k < r.shape(1); ++k) {
      if (!std::isfinite(r(i, k))) throw InputError(InputLocation{"", 0, "q"}, "row " + std::to_string(i) + ": not a finite number");
      out(i, k) = m.axes[static_cast<size_t>(k)].isRotary() ? r(i, k) * kDeg : r(i, k);
    }
  return out;
}

py::array_t<double> jointArray(const Machine& m, const JointMatrix& q) {
  py::array_t<double> out = toArray(q);
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < q.rows(); ++r)
    for (Eigen::Index k = 0; k < q.cols(); ++k)
      if (m.axes[static_cast<size_t>(k)].isRotary()) w(r, k) /= kDeg;
  return out;
}

DirectionMatrix directions(const py::object& dirs, const JointMatrix& q) {
  if (dirs.is_none()) return {};
  using IntArray = py::array_t<int, py::array::c_style | py::array::forcecast>;
  const auto a = IntArray(dirs);
  if (a.ndim() != 2 || a.shape(0) != q.rows() || a.shape(1) != q.cols())
    throw InputError(InputLocation{"", 0, "directions"}, "expected the shape of q");
  return Eigen::Map<const DirectionMatrix>(a.data(), q.rows(), q.cols());
}

Vec3 vec3(const std::vector<double>& v, const std::string& key) {
  if (v.size() != 3) throw InputError(InputLocation{"", 0, key}, "expected three numbers x,y,z");
  return {v[0], v[1], v[2]};
}

double quantity(const py::object& value, Dimension d, const std::string& key) {
  if (py::isinstance<py::str>(value)) return parseQuantityAs(value.cast<std::string>(), d, key);
  double v = 0;
  try {
    v = value.cast<double>();
  } catch (const py::cast_error&) {
    throw InputError(InputLocation{"", 0, key}, "expected a number (mm or rad) or a string with a unit such as '10 um'");
  }
  if (!std::isfinite(v) || std::abs(v) > largestMagnitude(d))
    throw InputError(InputLocation{"", 0, key}, "not a finite number within range");
  return v;
}

}  // namespace mtacc::python
