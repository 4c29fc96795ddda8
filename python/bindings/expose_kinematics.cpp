// Machine: forward and inverse kinematics, the parameter Jacobians and the TCP uncertainty of
// identified errors, on arrays of poses.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/kinematics_options.hpp"
#include "mtacc/workflows/tcp_uncertainty.hpp"

namespace mtacc::python {

void exposeKinematics(MachineBinding& machine) {
  machine
      .def("fk", [](const PythonMachine& s, const Array& q, const py::object& dirs, const OptionValues& options, bool errors) {
        const auto joints_ = joints(*s.machine, q);
        const auto d = directions(dirs, joints_);
        const auto& [actual, nominalModel] = s.compiled();
        ForwardOptions o = forwardOptions(errors ? errorsSchema() : forwardSchema(), options);
        o.errors = errors;
        ForwardResult r;
        {
          py::gil_scoped_release release;
          r = forwardKinematics(actual, nominalModel, joints_, d, o);
        }
        if (!errors) return py::make_tuple(toArray(r.tool.positions), toArray(r.tool.directions));
        return py::make_tuple(toArray(r.error.leftCols<3>(), 1e3), toArray(r.error.rightCols<3>(), 1e6));
      })
      // tcps and tools given: a path's targets, the options only how to solve them; else the
      // options' own single target (tcp, tool).
      .def("ik", [](const PythonMachine& s, const std::vector<std::vector<double>>& tcps, const std::vector<std::vector<double>>& tools,
                    const OptionValues& options) {
        InverseRequest request = tcps.empty() ? inverseRequest(s, options) : inverseSolving(s, options);
        for (const auto& p : tcps) request.positions.push_back(vec3(p, "tcps"));
        for (const auto& t : tools) request.directions.push_back(vec3(t, "tools"));
        const auto& [actual, nominalModel] = s.compiled();
        const auto r = inverseKinematics(actual, nominalModel, request);
        std::vector<const std::vector<double>*> rows;
        for (const auto& solution : r.solutions) rows.push_back(&solution.q);
        for (const auto& solution : r.withErrors) rows.push_back(&solution.q);
        JointMatrix q(static_cast<Eigen::Index>(rows.size()), s.machine->commandedCount());
        for (size_t i = 0; i < rows.size(); ++i)
          for (int k = 0; k < q.cols(); ++k) q(static_cast<Eigen::Index>(i), k) = (*rows[i])[static_cast<size_t>(k)];
        return py::make_tuple(toPython(toJson(r)), jointArray(*s.machine, q));
      })
      .def("jacobian", [](const PythonMachine& s, const Array& q, const std::vector<std::string>& names) {
        const auto r = parameterJacobians(s, joints(*s.machine, q), names);
        const auto p = static_cast<py::ssize_t>(r.parameters.size());
        py::array_t<double> out({static_cast<py::ssize_t>(r.perPose.size()), py::ssize_t{6}, p});
        auto w = out.mutable_unchecked<3>();
        for (size_t i = 0; i < r.perPose.size(); ++i)
          for (py::ssize_t row = 0; row < 6; ++row)
            for (py::ssize_t k = 0; k < p; ++k) w(static_cast<py::ssize_t>(i), row, k) = r.perPose[i](row, k);
        return py::make_tuple(r.parameters, out);
      })
      .def("tcp_uncertainty", [](const PythonMachine& s, const Array& q) {
        const auto poses = joints(*s.machine, q);
        std::vector<Vec3> u;
        {
          py::gil_scoped_release release;
          u = tcpUncertainty(s, poses);
        }
        Eigen::MatrixXd out(static_cast<Eigen::Index>(u.size()), 3);
        for (size_t i = 0; i < u.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = u[i].transpose();
        return toArray(out, 1e3);
      });
}

}  // namespace mtacc::python
