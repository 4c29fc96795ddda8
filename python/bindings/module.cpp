// The Python module mtacc._mtacc: each function calls one workflow of the library and returns
// its result as the CLI's --json prints it (converted to Python objects), or as numpy arrays
// for the batch kinematics. Units at this interface are those of the CLI: mm and degrees for
// axis positions, mm for the TCP, um and urad for errors.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/version.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/io/measurement_csv.hpp"
#include "mtacc/io/structure_yaml.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/workflows/budget.hpp"
#include "mtacc/workflows/check.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/thermal_drift.hpp"
#include "mtacc/workflows/thermal_state_summary.hpp"
#include "mtacc/workflows/cone_study.hpp"
#include "mtacc/workflows/cubic_identification.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"
#include "mtacc/workflows/dynamics.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/identified_errors.hpp"
#include "mtacc/workflows/program_deviation.hpp"
#include "mtacc/workflows/tcp_uncertainty.hpp"
#include "mtacc/workflows/kinematics_batch.hpp"
#include "mtacc/workflows/measurement_runs.hpp"
#include "mtacc/workflows/option_schemas.hpp"
#include "mtacc/workflows/plates.hpp"
#include "mtacc/workflows/positioning.hpp"
#include "mtacc/workflows/report_paths.hpp"
#include "mtacc/workflows/stiffness.hpp"
#include "mtacc/io/pose_text.hpp"
#include "mtacc/workflows/compensation.hpp"
#include "mtacc/workflows/recorded_decomposition.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

namespace py = pybind11;
using namespace mtacc;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int, py::array::c_style | py::array::forcecast>;

py::object toPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

template <class Matrix>
py::array_t<double> toArray(const Matrix& m, double scale = 1.0) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index k = 0; k < m.cols(); ++k) w(i, k) = m(i, k) * scale;
  return out;
}

// A height map as a (ny, nx) float32 array, row j at y(j), scaled (e.g. mm -> um).
py::array_t<float> heightArray(const HeightMap& m, double scale) {
  py::array_t<float> out({static_cast<py::ssize_t>(m.grid.ny), static_cast<py::ssize_t>(m.grid.nx)});
  float* w = out.mutable_data();
  for (size_t k = 0; k < m.height.size(); ++k) w[k] = static_cast<float>(m.height[k] * scale);
  return out;
}

// (n, axes) in mm / deg -> joint matrix in mm / rad.
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

DirectionMatrix directions(const py::object& dirs, const JointMatrix& q) {
  if (dirs.is_none()) return {};
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

}  // namespace

// The module's Machine: a setup whose compiled models are kept between calls, so that a
// pose at a time costs an evaluation, not a compilation; set_error drops them.
struct PythonMachine : MachineSetup {
  mutable std::optional<std::pair<KinematicModel, KinematicModel>> models;  // actual, nominal

  const std::pair<KinematicModel, KinematicModel>& compiled() const {
    if (!models) models.emplace(actual(), nominal());
    return *models;
  }
};

PYBIND11_MODULE(_mtacc, mod) {
  mod.doc() = "mtacc: geometric accuracy of multi-axis machine tools (C++ core)";
  mod.attr("__version__") = version();
  static py::exception<InputError> inputError(mod, "InputError", PyExc_ValueError);
  static py::exception<UnreachablePose> unreachable(mod, "UnreachablePose", inputError.ptr());
  mod.def("option_keys", [](const std::string& workflow) {
    const auto& schemas = workflowOptionSchemas();
    const auto it = schemas.find(workflow);
    if (it == schemas.end()) throw InputError({"", 0, "workflow"}, "no option schema for '" + workflow + "'");
    return it->second->keys();
  }, py::arg("workflow"));
  mod.def("option_schema_workflows", [] {
    std::vector<std::string> names;
    for (const auto& [name, schema] : workflowOptionSchemas()) names.push_back(name);
    return names;
  });
  mod.def("positioning", [](const std::string& path) { return toPython(toJson(evaluatePositioningFile(path))); }, py::arg("path"));
  mod.def("thermal_state", [](const std::string& machine, const std::string& thermal, int points) {
    return toPython(thermalStateSummary({machine, "", "", std::nullopt, thermal}, points));
  });
  mod.def("drift_test", [](const OptionValues& options, size_t seriesPoints) {
    const DriftTestRequest request = driftTestRequest(options);
    DriftTestEvaluation evaluation;
    {
      py::gil_scoped_release release;
      evaluation = evaluateDriftTest(request);
    }
    return toPython(toJson(evaluation, seriesPoints));
  });
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

  py::class_<PythonMachine>(mod, "Machine")
      .def(py::init([](const std::string& machine, const std::string& errors, const std::string& alignment, std::optional<double> load,
                       const std::string& thermal) { return PythonMachine{{loadMachineSetup({machine, errors, alignment, load, thermal})}, {}}; }),
           py::arg("machine"), py::arg("errors") = "", py::arg("alignment") = "", py::arg("load") = py::none(), py::arg("thermal") = "")
      .def("check", [](const PythonMachine& s) { return toPython(toJson(checkMachine(s))); })
      .def("error_unit", [](const PythonMachine& s, const std::string& name) {
        return findParameter(*s.machine, s.errors, name).dimension == Dimension::Length ? "mm" : "rad";
      })
      .def("get_error", [](const PythonMachine& s, const std::string& name) {
        return isoSign(name) * parameterValue(s.errors, findParameter(*s.machine, s.errors, name));
      })
      .def("set_error", [](PythonMachine& s, const std::string& name, const py::object& value) {
        auto errors = s.errors;
        const auto p = defineParameter(*s.machine, errors, name);
        setParameterValue(errors, p, isoSign(name) * quantity(value, p.dimension, name));
        s.errors = std::move(errors);
        s.models.reset();
      })
      .def("nonzero_errors", [](const PythonMachine& s) {
        py::dict d;
        for (const auto& p : nonZeroParameters(*s.machine, s.errors)) d[py::str(p.name)] = parameterValue(s.errors, p);
        return d;
      })
      .def("fk", [](const PythonMachine& s, const Array& q, const py::object& dirs, bool nominal, bool errors, int threads) {
        const auto joints_ = joints(*s.machine, q);
        const auto d = directions(dirs, joints_);
        const auto& [actual, nominalModel] = s.compiled();
        ForwardResult r;
        {
          py::gil_scoped_release release;
          r = forwardKinematics(actual, nominalModel, joints_, d, {nominal, errors, threads});
        }
        if (!errors) return py::make_tuple(toArray(r.tool.positions), toArray(r.tool.directions));
        return py::make_tuple(toArray(r.error.leftCols<3>(), 1e3), toArray(r.error.rightCols<3>(), 1e6));
      })
      .def("ik", [](const PythonMachine& s, const std::vector<std::vector<double>>& tcps, const std::vector<std::vector<double>>& tools,
                    const std::string& branch, bool all, bool withErrors, const std::string& near) {
        InverseRequest request;
        request.withErrors = withErrors;
        if (!near.empty()) request.options.hint = parsePose(*s.machine, near, "near", true);
        for (const auto& p : tcps) request.positions.push_back(vec3(p, "tcp"));
        for (const auto& t : tools) request.directions.push_back(vec3(t, "tool"));
        request.options.branch = parseTiltBranch(branch);
        request.all = all;
        const auto& [actual, nominalModel] = s.compiled();
        const auto r = inverseKinematics(actual, nominalModel, request);
        std::vector<const std::vector<double>*> rows;
        for (const auto& solution : r.solutions) rows.push_back(&solution.q);
        for (const auto& solution : r.withErrors) rows.push_back(&solution.q);
        JointMatrix q(static_cast<Eigen::Index>(rows.size()), s.machine->commandedCount());
        for (size_t i = 0; i < rows.size(); ++i)
          for (int k = 0; k < q.cols(); ++k)
            q(static_cast<Eigen::Index>(i), k) = s.machine->axes[static_cast<size_t>(k)].isRotary() ? (*rows[i])[static_cast<size_t>(k)] / kDeg
                                                                                                     : (*rows[i])[static_cast<size_t>(k)];
        return py::make_tuple(toPython(toJson(r)), toArray(q));
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
      .def("sensitivity_coefficient", [](const PythonMachine& s, const Array& q, const std::string& name, const py::object& epsilon,
                                         const std::vector<double>& direction) {
        const auto joints_ = joints(*s.machine, q);
        const auto p = findParameter(*s.machine, s.errors, name);
        const double eps = quantity(epsilon, p.dimension, "epsilon");
        if (eps == 0.0) throw InputError(InputLocation{"", 0, "epsilon"}, "must not be zero");
        const Vec3 normal = vec3(direction, "direction");
        if (!(normal.norm() > 1e-12)) throw InputError(InputLocation{"", 0, "direction"}, "has zero length");
        requireWithinTravel(*s.machine, joints_);
        return sensitivityCoefficient(s.machine, s.errors, {p, eps}, {joints_.row(0).data(), normal});
      })
      .def("working_volume_grid", [](const PythonMachine& s, int samples) {
        requireInRange(budgetSchema().at("samples"), samples);
        const auto g = workingVolumeGrid(*s.machine, samples);
        py::array_t<double> out = toArray(g);
        auto w = out.mutable_unchecked<2>();
        for (long r = 0; r < g.rows(); ++r)
          for (long k = 0; k < g.cols(); ++k)
            if (s.machine->axes[static_cast<size_t>(k)].isRotary()) w(r, k) /= kDeg;
        return out;
      })
      .def("budget", [](const PythonMachine& s, const OptionValues& options) {
        const BudgetOptions o = budgetOptions(options);
        BudgetResult r;
        {
          py::gil_scoped_release release;
          r = errorBudget(s, o);
        }
        return toPython(toJson(r));
      })
      .def("cone", [](const PythonMachine& s, const std::string& preset, double alpha, double beta, double radius,
                      const std::vector<double>& centre, double gamma, bool face, int points, const std::string& branch, double feed,
                      bool singleErrors, int monteCarlo, const std::string& limitsFile, const std::string& limitsYaml,
                      std::uint64_t seed) {
        ConeStudyOptions o;
        if (!preset.empty()) {
          const auto p = conePreset(preset);
          if (!p) throw InputError(InputLocation{"", 0, "preset"}, "unknown preset '" + preset + "'");
          o.spec = *p;
        } else {
          o.spec.alpha = alpha * kDeg;
          o.spec.beta = beta * kDeg;
          o.spec.radius = radius;
          o.spec.centre = vec3(centre, "centre");
          o.spec.gamma = gamma * kDeg;
        }
        o.spec.faceMilling = face;
        o.points = points;
        o.branch = parseTiltBranch(branch);
        o.feed = feed;
        o.singleErrors = singleErrors;
        o.monteCarlo = monteCarlo;
        o.limitsFile = limitsFile;
        o.limitsYaml = limitsYaml;
        o.seed = seed;
        ConeStudy r;
        {
          py::gil_scoped_release release;
          r = coneStudy(s, o);
        }
        return toPython(toJson(r));
      })
      .def("cubic", [](const PythonMachine& s, const std::string& test, double grid, double inset, bool sensitivities,
                       const std::vector<std::string>& parameters, double sensitivityGrid, int threads) {
        CubicTestOptions o;
        o.spec = loadCubicTest(test);
        o.gridSpacing = grid;
        o.inset = inset;
        o.sensitivities = sensitivities;
        o.sensitivityParameters = parameters;
        o.sensitivityGrid = sensitivityGrid;
        o.threads = threads;
        CubicTestStudy r;
        {
          py::gil_scoped_release release;
          r = cubicTestStudy(s, o);
        }
        py::dict out = toPython(toJson(r));
        const auto& g = r.actual.grid;
        out["grid"] = py::dict(py::arg("x0") = g.x0, py::arg("y0") = g.y0, py::arg("spacing") = g.spacing);
        out["heights_um"] = heightArray(r.actual, 1e3);
        out["referenced_deviation_um"] = heightArray(referencedDeviation(r), 1e3);
        py::list paths;
        for (const auto& z : r.path) paths.append(toArray(z.tips));
        out["tool_tips"] = paths;
        if (!r.sensitivities.empty()) {
          const auto& c = r.sensitivities.front().mapWithAlignment.grid;
          out["sensitivity_grid"] = py::dict(py::arg("x0") = c.x0, py::arg("y0") = c.y0, py::arg("spacing") = c.spacing);
          py::dict maps;
          for (const auto& k : r.sensitivities)
            maps[py::str(k.name)] = py::dict(py::arg("with_alignment") = heightArray(k.mapWithAlignment, 1.0),
                                             py::arg("on_table") = heightArray(k.mapOnTable, 1.0));
          out["sensitivity_maps"] = maps;
        }
        return out;
      })
      .def("cubic_identify", [](const PythonMachine& s, const std::string& zones, const std::vector<std::string>& parameters,
                                const std::string& test, const std::string& noise, const std::string& errorsOut) {
        CubicIdentificationRequest request;
        request.test = test;
        request.zonesFile = zones;
        request.parameters = parameters;
        if (!noise.empty()) request.noise = parseQuantityAs(noise, Dimension::Length, "noise");
        IdentificationOutcome out;
        {
          py::gil_scoped_release release;
          out = identifyFromZones(s, request);
        }
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, out, "errors_out");
        return toPython(toJson(out));
      })
      .def("cone_preset_name", [](const PythonMachine& s) { return conePresetName(*s.machine); })
      .def("fit_component", [](const PythonMachine& s, const std::string& file, const std::vector<double>& breaks, int pieces, int degree,
                               double significance, const py::object& period, double periodZero, double threshold, bool removeDisturbed,
                               const std::string& errorsOut) {
        ComponentFitRequest r{.file = file, .breaks = breaks, .pieces = pieces, .degree = degree, .significance = significance};
        if (!period.is_none()) r.period = period.cast<double>();
        r.periodZero = periodZero;
        r.disturbanceThreshold = threshold;
        r.removeDisturbed = removeDisturbed;
        const auto study = fitComponentFile(s, r);
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, *study.machine, study.errors, identificationRecord(study), "errors_out");
        return toPython(toJson(study));
      })
      .def("decompose", [](const PythonMachine& s, const std::string& setFile, size_t seriesPoints, const std::string& driftFrame) {
        const auto set = loadDecompositionSetWithDriftFrame(setFile, driftFrame, "drift_frame");
        RecordedDecomposition result;
        {
          py::gil_scoped_release release;
          result = decomposeRecordedSet(s, set);
        }
        return toPython(toJson(result, seriesPoints));
      })
      .def("simulate_motion", [](const PythonMachine& s, const std::string& program, const std::string& folder, const std::vector<double>& feeds,
                                 const std::string& structure, const std::string& noise, double acceleration, double jerkTimeMs,
                                 const std::vector<double>& kv, const std::vector<double>& feedForward, double clockOffsetMs, std::uint64_t seed,
                                 const std::string& format) {
        MotionSimulationRequest request;
        request.program = program;
        request.folder = folder;
        if (!feeds.empty()) request.feeds = feeds;
        request.structure = structure;
        request.noise = parseQuantityAs(noise, Dimension::Length, "noise");
        request.limits.acceleration = acceleration;
        request.limits.jerkTime = jerkTimeMs * 1e-3;
        request.positionGains = kv;
        request.feedForwards = feedForward;
        request.format = signalFormatNamed(format, "format");
        request.clockOffset = clockOffsetMs * 1e-3;
        request.seed = seed;
        MotionSimulation simulation;
        {
          py::gil_scoped_release release;
          simulation = simulateMotion(s, request);
        }
        return toPython(toJson(simulation));
      })
      .def("identify_plates", [](const PythonMachine& s, const std::vector<std::string>& files, double piece) {
        PlateIdentificationStudy study;
        {
          py::gil_scoped_release release;
          study = identifyPlateFiles(s, files, piece);
        }
        return toPython(toJson(study));
      })
      .def("stiffness", [](const PythonMachine& s, int samples) { return toPython(toJson(summariseStiffness(s, samples))); })
      .def("compensation_tables",
           [](const PythonMachine& s, const std::array<int, 3>& nodes, const std::string& pose, int functions, int linuxcncType,
              const std::string& checkProgram) {
             CompensationTablesRequest request;
             request.checkProgram = checkProgram;
             request.grid.counts = nodes;
             if (!pose.empty()) request.grid.pose = parsePose(*s.machine, pose, "pose", true);
             request.oneAxisFunctions = functions;
             request.linuxcncType = linuxcncType;
             CompensationTablesResult r;
             {
               py::gil_scoped_release release;
               r = compensationTables(s, request);
             }
             nlohmann::json j = toJson(r);
             j["contents"] = nlohmann::json::object();
             for (const auto& [name, content] : r.files) j["contents"][name] = content;
             return toPython(j);
           })
      .def("tcp_uncertainty",
           [](const PythonMachine& s, const Array& q) {
             const auto poses = joints(*s.machine, q);
             std::vector<Vec3> u;
             {
               py::gil_scoped_release release;
               u = tcpUncertainty(s, poses);
             }
             Eigen::MatrixXd out(static_cast<Eigen::Index>(u.size()), 3);
             for (size_t i = 0; i < u.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = u[i].transpose();
             return toArray(out, 1e3);
           })
      .def("deviation",
           [](const PythonMachine& s, const std::string& program, const std::string& intended, const std::map<int, double>& toolLengths,
              double step) {
             ProgramDeviationResult r;
             {
               py::gil_scoped_release release;
               r = programDeviationFile(s, {program, intended, toolLengths, {step}});
             }
             return toPython(toJson(r));
           })
      .def("compensate_program",
           [](const PythonMachine& s, const std::string& path, const std::map<int, double>& toolLengths, std::optional<double> tolerance,
              std::optional<double> directionTolerance, const std::string& checkErrors) {
             ProgramCompensationRequest request;
             request.programFile = path;
             request.toolLengths = toolLengths;
             request.checkErrorsFile = checkErrors;
             if (tolerance) request.options.tolerance = *tolerance;
             if (directionTolerance) request.options.directionTolerance = *directionTolerance;
             ProgramCompensationResult r;
             {
               py::gil_scoped_release release;
               r = compensateProgramFile(s, request);
             }
             nlohmann::json j = toJson(r);
             j["gcode"] = r.gcode;
             return toPython(j);
           })
      .def("compare_plate", [](const PythonMachine& s, const std::string& path) { return toPython(toJson(comparePlateFile(s, path))); })
      .def("simulate_plate", [](const PythonMachine& s, const std::string& output, const std::string& header, const std::string& noise,
                                std::uint64_t seed) {
        PlateSimulationRequest r;
        r.output = output;
        r.layout = parsePlateLayout(*s.machine, header, "layout");
        r.noise = noise;
        r.seed = seed;
        simulatePlateFile(s, r);
      })
      .def("simulate_component", [](const PythonMachine& s, const std::string& component, const std::string& output, double step, int runs,
                                    const std::string& noise, const std::vector<double>& abbe, const std::string& disturbance,
                                    double interval, const std::string& settling, double settlingTime, std::uint64_t seed) {
        ComponentSimulationRequest r{.component = component, .output = output, .step = step, .runs = runs, .noise = noise};
        if (abbe.size() != 3) throw InputError(InputLocation{"", 0, "abbe_offset"}, "expected (dx, dy, dz) in mm");
        r.abbeOffset = Vec3(abbe[0], abbe[1], abbe[2]);
        r.disturbance = disturbance;
        r.disturbanceInterval = interval;
        r.settling = settling;
        r.settlingTime = settlingTime;
        r.seed = seed;
        simulateComponentFile(s, r);
      })
      .def("simulate", [](const PythonMachine& s, const std::string& plan, const py::object& noise, std::uint64_t seed,
                          const std::string& outputDir, const std::string& setupErrors) {
        SimulationOptions o;
        o.noise = quantity(noise, Dimension::Length, "noise");
        o.setupErrors = parseSetupErrors(setupErrors, "setup");
        o.seed = seed;
        o.output = outputDir;
        o.outputIsFolder = true;
        return toPython(toJson(simulatePlan(s, plan, o)));
      })
      .def("read_measurement", [](const PythonMachine& s, const std::string& path) {
        return toPython(runJson(*s.machine, readMeasurementCsv(s.nominal(), path)));
      })
      .def("evaluate_ballbar", [](const PythonMachine& s, const std::string& path) { return toPython(toJson(evaluateBallbarFile(s, path))); })
      .def("evaluate_rtest", [](const PythonMachine& s, const std::string& path) { return toPython(toJson(evaluateRTestFile(s, path))); })
      .def("observability", [](const PythonMachine& s, const OptionValues& options) {
        return toPython(toJson(planObservability(s, identificationRequest(observabilitySchema(), options))));
      })
      .def("identify", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const IdentificationRequest request = identificationRequest(identificationSchema(), options);
        IdentificationOutcome out;
        {
          py::gil_scoped_release release;
          out = identifyParameters(s, request);
        }
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, out, "errors_out");
        return toPython(toJson(out));
      })
      .def("xy_circle", [](const PythonMachine& s) {
        const auto r = xyCircleTest(s);
        return r ? toPython(toJson(*r)) : py::none().cast<py::object>();
      })
      .def("tilted_circle", [](const PythonMachine& s) {
        const auto r = tiltedCircleTest(s);
        return r ? toPython(toJson(*r)) : py::none().cast<py::object>();
      });

  py::class_<StructureModel>(mod, "Structure")
      .def(py::init([](const std::string& pathOrName) { return loadStructure(pathOrName); }), py::arg("model"))
      .def_readonly("name", &StructureModel::name)
      .def("positions", [](const StructureModel& m, const std::string& at) { return structurePositions(m, at); })
      .def("modes", [](const StructureModel& m, const std::string& at, int count) {
        return toPython(toJson(structureModes(m, structurePositions(m, at)), count));
      })
      .def("frf", [](const StructureModel& m, const std::vector<double>& frequencies, const std::string& at, const std::string& method) {
        return toPython(toJson(structureFrf(m, {structurePositions(m, at), frequencies, method})));
      })
      .def("acceleration_response", [](const StructureModel& m, const std::string& at) {
        return toPython(toJson(structureAcceleration(m, structurePositions(m, at))));
      })
      .def("map", [](const StructureModel& m, const std::string& quantity, const std::string& axisA, const std::string& axisB,
                     int countA, int countB, const std::string& at) {
        MapResult r;
        const MapRequest request{quantity, {axisA, axisB, countA, countB, structurePositions(m, at)}};
        {
          py::gil_scoped_release release;
          r = structureMap(m, request);
        }
        return toPython(toJson(r));
      })
      .def("describe", [](const StructureModel& m) { return toPython(structureJson(m)); });
}
