// The Python module mtacc._mtacc: a machine with its errors, batch kinematics on numpy
// arrays, sensitivities and the error budget. Units at this interface are those of the CLI:
// mm and degrees for axis positions, mm for the TCP, um and urad for errors.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/errors/error_yaml.hpp"
#include "mtacc/kinematics/budget.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/inverse.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/machine/machine_yaml.hpp"
#include "mtacc/procedures/monte_carlo.hpp"
#include "py_machine.hpp"

namespace py = pybind11;
using namespace mtacc;
using mtacc::python::Array;
using mtacc::python::PyMachine;
using mtacc::python::bindDynamics;
using mtacc::python::bindMeasurement;

namespace {

py::array_t<double> toArray(const double* data, py::ssize_t rows, py::ssize_t cols) {
  py::array_t<double> out({rows, cols});
  std::copy(data, data + rows * cols, out.mutable_data());
  return out;
}

py::dict poseDict(const Machine& m, const std::vector<double>& q) {
  py::dict d;
  for (int i = 0; i < m.commandedCount(); ++i) {
    const Axis& a = m.axes[static_cast<size_t>(i)];
    d[py::str(a.name)] = a.isRotary() ? q[static_cast<size_t>(i)] / kDeg : q[static_cast<size_t>(i)];
  }
  return d;
}

double parseValue(const py::object& value, Dimension dim, const std::string& name) {
  if (py::isinstance<py::str>(value)) {
    std::string reason;
    const auto q = parseQuantity(value.cast<std::string>(), &reason);
    if (!q) throw InputError(InputLocation{"", 0, name}, reason);
    if (q->dimension != dim) throw InputError(InputLocation{"", 0, name}, std::string("expected ") + withArticle(dim));
    return q->value;
  }
  return value.cast<double>();
}

// Values given under a source's alias convert with its sign (iso = sign * source).
double aliasSign(const std::string& name) {
  const auto alias = findAlias(name);
  return alias && !alias->composite() ? alias->terms[0].sign : 1.0;
}

Parameter findParameterOrThrow(PyMachine& m, const std::string& name) {
  try {
    return findParameter(m.machine(), m.errors(), name);
  } catch (const std::invalid_argument& e) {
    throw InputError(InputLocation{"", 0, name}, e.what());
  }
}

}  // namespace

PYBIND11_MODULE(_mtacc, mod) {
  mod.doc() = "mtacc: geometric accuracy of multi-axis machine tools (C++ core)";
  static py::exception<InputError> inputError(mod, "InputError", PyExc_ValueError);
  static py::exception<UnreachablePose> unreachable(mod, "UnreachablePose", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      inputError(e.what());
    } catch (const UnreachablePose& e) {
      unreachable((std::string("unreachable pose: ") + e.what()).c_str());
    }
  });

  bindDynamics(mod);
  auto machineClass = py::class_<PyMachine>(mod, "Machine");
  bindMeasurement(machineClass);
  machineClass
      .def(py::init<const std::string&, const std::string&>(), py::arg("machine"), py::arg("errors") = "")
      .def_property_readonly("name", [](const PyMachine& m) { return m.machine().name; })
      .def_property_readonly("file", [](const PyMachine& m) { return m.machine().sourceFile; })
      .def_property_readonly("structure", [](const PyMachine& m) { return m.machine().structure.text; })
      .def_property_readonly("structure_tool_first", [](const PyMachine& m) { return m.machine().structure.toolFirst(); })
      .def_property_readonly("axis_names",
                             [](const PyMachine& m) {
                               std::vector<std::string> n;
                               for (const auto& a : m.machine().axes)
                                 if (a.commanded()) n.push_back(a.name);
                               return n;
                             })
      .def_property_readonly("axes",
                             [](const PyMachine& m) {
                               py::list out;
                               const Machine& mach = m.machine();
                               auto chainOf = [&](int i) {
                                 for (int k : mach.toolChain)
                                   if (k == i) return "tool";
                                 return "workpiece";
                               };
                               for (int i = 0; i < static_cast<int>(mach.axes.size()); ++i) {
                                 const Axis& a = mach.axes[static_cast<size_t>(i)];
                                 py::dict d;
                                 d["name"] = a.name;
                                 d["type"] = a.type == AxisType::Linear ? "linear" : a.type == AxisType::Rotary ? "rotary" : "spindle";
                                 d["side"] = chainOf(i);
                                 d["direction"] = std::vector<double>{a.direction.x(), a.direction.y(), a.direction.z()};
                                 d["location_mm"] = std::vector<double>{a.location.x(), a.location.y(), a.location.z()};
                                 d["offset_mm"] = std::vector<double>{a.offset.x(), a.offset.y(), a.offset.z()};
                                 d["error_frame"] = a.errorFrame == ErrorFrame::Fixed ? "fixed" : "moving";
                                 const double f = a.isRotary() ? 1.0 / kDeg : 1.0;
                                 if (a.travel) d["travel"] = std::vector<double>{a.travel->min * f, a.travel->max * f};
                                 else d["travel"] = py::none();
                                 out.append(d);
                               }
                               return out;
                             })
      .def_property_readonly("tool_chain",
                             [](const PyMachine& m) {
                               std::vector<std::string> n;
                               for (int i : m.machine().toolChain) n.push_back(m.machine().axes[static_cast<size_t>(i)].name);
                               return n;
                             })
      .def_property_readonly("workpiece_chain",
                             [](const PyMachine& m) {
                               std::vector<std::string> n;
                               for (int i : m.machine().workpieceChain) n.push_back(m.machine().axes[static_cast<size_t>(i)].name);
                               return n;
                             })
      .def_property_readonly("tool_direction",
                             [](const PyMachine& m) {
                               const Vec3& d = m.machine().toolDirection;
                               return std::vector<double>{d.x(), d.y(), d.z()};
                             })
      .def("parameter_names",
           [](PyMachine& m) {
             std::vector<std::string> n;
             for (const auto& p : parameterCatalogue(m.machine(), m.errors())) n.push_back(p.name);
             return n;
           })
      .def("error_unit",
           [](PyMachine& m, const std::string& name) {
             return findParameterOrThrow(m, name).dimension == Dimension::Length ? "mm" : "rad";
           })
      .def("get_error",
           [](PyMachine& m, const std::string& name) {
             return aliasSign(name) * parameterValue(m.errors(), findParameterOrThrow(m, name));
           })
      .def("set_error",
           [](PyMachine& m, const std::string& name, const py::object& value) {
             const auto p = findParameterOrThrow(m, name);
             setParameterValue(m.errors(), p, aliasSign(name) * parseValue(value, p.dimension, name));
           })
      .def("nonzero_errors",
           [](PyMachine& m) {
             py::dict d;
             for (const auto& p : nonZeroParameters(m.machine(), m.errors())) d[py::str(p.name)] = parameterValue(m.errors(), p);
             return d;
           })
      .def(
          "fk",
          [](PyMachine& m, const Array& q, const py::object& dirs, bool nominal) {
            const auto joints = m.joints(q);
            m.checkTravel(joints);
            const auto d = m.directions(dirs, joints.rows());
            const auto model = nominal ? compileNominal(m.shared()) : compile(m.shared(), m.errors());
            PointMatrix pos, dir;
            {
              py::gil_scoped_release release;
              toolPoints(model, joints, d, pos, dir, 0);
            }
            return py::make_tuple(toArray(pos.data(), pos.rows(), 3), toArray(dir.data(), dir.rows(), 3));
          },
          py::arg("q"), py::arg("directions") = py::none(), py::arg("nominal") = false)
      .def(
          "tcp_errors",
          [](PyMachine& m, const Array& q, const py::object& dirs) {
            const auto joints = m.joints(q);
            m.checkTravel(joints);
            const auto d = m.directions(dirs, joints.rows());
            const auto actual = compile(m.shared(), m.errors());
            const auto nominal = compileNominal(m.shared());
            Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> e;
            {
              py::gil_scoped_release release;
              e = toolErrors(actual, nominal, joints, d, 0);
            }
            for (long r = 0; r < e.rows(); ++r) {
              e.row(r).head<3>() *= 1e3;
              e.row(r).tail<3>() *= 1e6;
            }
            return toArray(e.data(), e.rows(), 6);
          },
          py::arg("q"), py::arg("directions") = py::none())
      .def(
          "ik",
          [](PyMachine& m, std::vector<double> tcp, std::vector<double> tool, const std::string& branch, bool all) {
            if (tcp.size() != 3 || tool.size() != 3) throw InputError(InputLocation{"", 0, "tcp/tool"}, "expected three numbers x,y,z");
            IkOptions o;
            o.branch = parseTiltBranch(branch);
            const auto nominal = compileNominal(m.shared());
            const Vec3 p(tcp[0], tcp[1], tcp[2]), t(tool[0], tool[1], tool[2]);
            std::vector<IkSolution> sols;
            if (all) sols = inverseKinematics(nominal, p, t, o).solutions;
            else sols = {solveIk(nominal, p, t, o)};
            py::list out;
            for (const auto& s : sols)
              out.append(py::dict(py::arg("pose") = poseDict(m.machine(), s.q), py::arg("singular") = s.singular,
                                  py::arg("free_axis") = s.singularAxis, py::arg("within_travel") = s.withinTravel,
                                  py::arg("travel_violation") = s.travelViolation));
            return out;
          },
          py::arg("tcp"), py::arg("tool") = std::vector<double>{0, 0, 1}, py::arg("branch") = "auto", py::arg("all") = false)
      .def(
          "ik_path",
          [](PyMachine& m, const Array& tcps, const Array& tools, const std::string& branch) {
            const auto p = tcps.unchecked<2>();
            const auto t = tools.unchecked<2>();
            if (p.shape(1) != 3 || t.shape(1) != 3 || p.shape(0) != t.shape(0))
              throw InputError(InputLocation{"", 0, "tcps/tools"}, "expected two (n, 3) arrays of the same length");
            std::vector<Vec3> ps, ts;
            for (py::ssize_t i = 0; i < p.shape(0); ++i) {
              ps.emplace_back(p(i, 0), p(i, 1), p(i, 2));
              ts.emplace_back(t(i, 0), t(i, 1), t(i, 2));
            }
            IkOptions o;
            o.branch = parseTiltBranch(branch);
            const auto path = solveIkPath(compileNominal(m.shared()), ps, ts, o);
            py::array_t<double> out({static_cast<py::ssize_t>(path.size()), static_cast<py::ssize_t>(m.axisCount())});
            auto w = out.mutable_unchecked<2>();
            for (size_t i = 0; i < path.size(); ++i)
              for (int k = 0; k < m.axisCount(); ++k)
                w(static_cast<py::ssize_t>(i), k) = m.machine().axes[static_cast<size_t>(k)].isRotary() ? path[i].q[static_cast<size_t>(k)] / kDeg
                                                                                                   : path[i].q[static_cast<size_t>(k)];
            return out;
          },
          py::arg("tcps"), py::arg("tools"), py::arg("branch") = "auto")
      .def(
          "jacobian",
          [](PyMachine& m, Array q, const py::object& params) {
            const auto joints = m.joints(Array(q.reshape({1L, static_cast<long>(q.size())})));
            std::vector<Parameter> ps;
            if (params.is_none()) ps = parameterCatalogue(m.machine(), m.errors());
            else
              for (const auto& n : params.cast<std::vector<std::string>>()) ps.push_back(findParameterOrThrow(m, n));
            const auto jac = parameterJacobian(compile(m.shared(), m.errors()), ps, joints.row(0).data());
            std::vector<std::string> names;
            for (const auto& p : ps) names.push_back(p.name);
            py::array_t<double> out({6L, static_cast<long>(ps.size())});
            auto w = out.mutable_unchecked<2>();
            for (long r = 0; r < 6; ++r)
              for (long c = 0; c < static_cast<long>(ps.size()); ++c) w(r, c) = jac(r, c);
            return py::make_tuple(names, out);
          },
          py::arg("q"), py::arg("params") = py::none(),
          "Derivative of (dx, dy, dz [mm], rotation [rad]) with respect to each parameter (mm or rad)")
      .def(
          "sensitivity_coefficient",
          [](PyMachine& m, Array q, const std::string& name, const py::object& epsilon, std::vector<double> direction) {
            if (direction.size() != 3) throw InputError(InputLocation{"", 0, "direction"}, "expected three numbers");
            const auto joints = m.joints(Array(q.reshape({1L, static_cast<long>(q.size())})));
            const auto p = findParameterOrThrow(m, name);
            const double eps = parseValue(epsilon, p.dimension, "epsilon");
            if (eps == 0.0) throw InputError(InputLocation{"", 0, "epsilon"}, "must not be zero");
            return sensitivityCoefficient(m.shared(), m.errors(), p, eps, joints.row(0).data(),
                                          Vec3(direction[0], direction[1], direction[2]));
          },
          py::arg("q"), py::arg("parameter"), py::arg("epsilon"), py::arg("direction"),
          "Seed 001 eq. 15: k = E / epsilon, E the TCP deviation along direction [mm] for the error epsilon alone")
      .def(
          "cone",
          [](PyMachine& m, double alpha, double beta, double radius, std::vector<double> centre, double gamma, bool face,
             int points, const std::string& branch, double feed, bool singleErrors, int monteCarlo, const std::string& limitsFile,
             std::uint64_t seed) {
            if (centre.size() != 3) throw InputError(InputLocation{"", 0, "centre"}, "expected three numbers x,y,z");
            if (points < 8 || points > 1000000) throw InputError(InputLocation{"", 0, "points"}, "must be between 8 and 1000000");
            ConeSpec spec;
            spec.alpha = alpha * kDeg;
            spec.beta = beta * kDeg;
            spec.radius = radius;
            spec.centre = Vec3(centre[0], centre[1], centre[2]);
            spec.gamma = gamma * kDeg;
            spec.faceMilling = face;
            const auto nominal = compileNominal(m.shared());
            const auto path = conePath(spec, points);
            const auto motion = coneMotion(nominal, spec, path, parseTiltBranch(branch), feed);
            const Machine& mach = m.machine();
            const auto n = static_cast<py::ssize_t>(path.phi.size());
            const auto axes = static_cast<py::ssize_t>(mach.commandedCount());
            const py::ssize_t three = 3;
            py::array_t<double> phi(n), q({n, axes}), normals({n, three}), tools({n, three}), points3({n, three}),
                machineNormals({n, three});
            auto wq = q.mutable_unchecked<2>();
            auto wm = machineNormals.mutable_unchecked<2>();
            auto wn = normals.mutable_unchecked<2>();
            auto wt = tools.mutable_unchecked<2>();
            auto wp = points3.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < n; ++i) {
              phi.mutable_at(i) = path.phi[static_cast<size_t>(i)] / kDeg;
              for (py::ssize_t k = 0; k < axes; ++k)
                wq(i, k) = mach.axes[static_cast<size_t>(k)].isRotary() ? motion.q[static_cast<size_t>(i)][static_cast<size_t>(k)] / kDeg
                                                                       : motion.q[static_cast<size_t>(i)][static_cast<size_t>(k)];
              const Vec3 nm = workpiecePose(nominal, motion.q[static_cast<size_t>(i)].data(), nullptr).linear() *
                              path.normals[static_cast<size_t>(i)];
              for (int c = 0; c < 3; ++c) {
                wm(i, c) = nm[c];
                wn(i, c) = path.normals[static_cast<size_t>(i)][c];
                wt(i, c) = path.tools[static_cast<size_t>(i)][c];
                wp(i, c) = path.points[static_cast<size_t>(i)][c];
              }
            }
            py::list axisStats;
            for (size_t k = 0; k < motion.axes.size(); ++k) {
              const auto& a = motion.axes[k];
              const double f = mach.axes[k].isRotary() ? 1.0 / kDeg : 1.0;
              std::vector<double> rev;
              for (double p : a.reversalsPhi) rev.push_back(p / kDeg);
              axisStats.append(py::dict(py::arg("axis") = a.axis, py::arg("min") = a.min * f, py::arg("max") = a.max * f,
                                        py::arg("range") = a.range * f, py::arg("reversals_phi_deg") = rev,
                                        py::arg("max_speed_per_s") = a.maxSpeed * f / 60,
                                        py::arg("max_acceleration_per_s2") = a.maxAcceleration * f / 3600));
            }
            py::dict out(py::arg("phi") = phi, py::arg("q") = q, py::arg("normals") = normals,
                         py::arg("normals_machine") = machineNormals, py::arg("tools") = tools,
                         py::arg("points") = points3, py::arg("axes") = axisStats, py::arg("warnings") = motion.warnings);
            auto deviationArray = [](const std::vector<double>& v) {
              py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
              for (size_t i = 0; i < v.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = v[i] * 1e3;
              return a;
            };
            const auto nonZero = nonZeroParameters(mach, m.errors());
            if (!nonZero.empty()) {
              const auto r = coneFormErrorExact(compile(m.shared(), m.errors()), spec, path, motion);
              out["form_error_um"] = r.formError * 1e3;
              out["deviation_um"] = deviationArray(r.deviation);
              out["raw_deviation_um"] = deviationArray(r.rawDeviation);
            }
            if (singleErrors) {
              py::list singles;
              for (const auto& p : nonZero) {
                ErrorModel single = m.errors();
                for (const auto& other : parameterCatalogue(mach, single))
                  if (other.name != p.name) setParameterValue(single, other, 0.0);
                const auto r = coneFormErrorExact(compile(m.shared(), single), spec, path, motion);
                singles.append(py::dict(py::arg("error") = p.name, py::arg("form_error_um") = r.formError * 1e3,
                                        py::arg("type") = toString(formErrorType(r.deviation)),
                                        py::arg("deviation_um") = deviationArray(r.deviation),
                                        py::arg("raw_deviation_um") = deviationArray(r.rawDeviation)));
              }
              out["single_errors"] = singles;
            }
            if (monteCarlo > 0) {
              const auto limits = loadErrorLimits(mach, limitsFile.empty() ? bundledDataDir() + "/limits/seed000-table3.9.yaml" : limitsFile);
              ConeMonteCarlo mc;
              {
                py::gil_scoped_release release;
                mc = coneMonteCarlo(m.shared(), limits, spec, path, motion, monteCarlo, seed);
              }
              const auto& st = mc.statistics;
              out["monte_carlo"] = py::dict(py::arg("form_errors_um") = deviationArray(mc.formErrors),
                                            py::arg("min_um") = st.min * 1e3, py::arg("lower_quartile_um") = st.lowerQuartile * 1e3,
                                            py::arg("median_um") = st.median * 1e3, py::arg("upper_quartile_um") = st.upperQuartile * 1e3,
                                            py::arg("max_um") = st.max * 1e3);
            }
            return out;
          },
          py::arg("alpha") = 45.0, py::arg("beta") = 30.0, py::arg("radius") = 40.0,
          py::arg("centre") = std::vector<double>{-65, 0, 150}, py::arg("gamma") = 0.0, py::arg("face_milling") = false,
          py::arg("points") = 720, py::arg("branch") = "negative", py::arg("feed") = 500.0, py::arg("single_errors") = false,
          py::arg("monte_carlo") = 0, py::arg("limits") = "", py::arg("seed") = 1,
          "The cone-frustum test piece of seed 000 (angles in deg, lengths in mm, deviations in um)")
      .def(
          "working_volume_grid",
          [](PyMachine& m, int samples) {
            if (samples < 2 || samples > 50) throw InputError(InputLocation{"", 0, "samples"}, "must be between 2 and 50");
            const auto g = workingVolumeGrid(m.machine(), samples);
            py::array_t<double> out({static_cast<py::ssize_t>(g.rows()), static_cast<py::ssize_t>(g.cols())});
            auto w = out.mutable_unchecked<2>();
            for (long r = 0; r < g.rows(); ++r)
              for (long k = 0; k < g.cols(); ++k)
                w(r, k) = m.machine().axes[static_cast<size_t>(k)].isRotary() ? g(r, k) / kDeg : g(r, k);
            return out;
          },
          py::arg("samples") = 5, "The budget's grid: samples positions per axis across the travel (mm, deg)")
      .def(
          "budget",
          [](PyMachine& m, int samples, const py::object& length, const py::object& angle) {
            std::vector<BudgetItem> items;
            std::string basis;
            const bool atMagnitude = !length.is_none() || !angle.is_none();
            if (atMagnitude || nonZeroParameters(m.machine(), m.errors()).empty()) {
              const double l = length.is_none() ? 0.01 : parseValue(length, Dimension::Length, "length");
              const double a = angle.is_none() ? 30e-6 : parseValue(angle, Dimension::Angle, "angle");
              items = budgetItemsAtMagnitude(m.machine(), l, a);
              basis = "magnitude";
            } else {
              items = budgetItemsOfModel(m.machine(), m.errors());
              basis = "model";
            }
            if (samples < 2 || samples > 50) throw InputError(InputLocation{"", 0, "samples"}, "must be between 2 and 50");
            const auto grid = workingVolumeGrid(m.machine(), samples);
            std::vector<BudgetEntry> entries;
            {
              py::gil_scoped_release release;
              entries = errorBudget(m.shared(), items, grid, 0);
            }
            py::list out;
            for (const auto& e : entries)
              out.append(py::dict(py::arg("error") = e.name,
                                  py::arg("magnitude") = e.dimension == Dimension::Length ? e.magnitude * 1e3 : e.magnitude * 1e6,
                                  py::arg("unit") = e.dimension == Dimension::Length ? "um" : "urad",
                                  py::arg("max_position_error_um") = e.maxPositionError * 1e3,
                                  py::arg("max_orientation_error_urad") = e.maxOrientationError * 1e6,
                                  py::arg("worst_pose") = poseDict(m.machine(), e.worstPose)));
            return py::dict(py::arg("basis") = basis, py::arg("poses") = grid.rows(), py::arg("entries") = out);
          },
          py::arg("samples") = 5, py::arg("length") = py::none(), py::arg("angle") = py::none());
}
