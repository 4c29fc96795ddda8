// Measurement bindings of mtacc.Machine: simulated test plans, ballbar evaluation,
// identification and observability. Units as the CLI's: mm and deg for poses, um and urad
// for readings and errors.
#include <pybind11/stl.h>

#include <filesystem>
#include <random>

#include "mtacc/io/atomic_file.hpp"
#include "mtacc/measurement/circular_test.hpp"
#include "mtacc/measurement/identification.hpp"
#include "mtacc/measurement/measurement_csv.hpp"
#include "mtacc/measurement/simulation.hpp"
#include "mtacc/measurement/test_plan.hpp"
#include "py_machine.hpp"

namespace mtacc::python {
namespace {

double display(double v, Dimension d) { return d == Dimension::Length ? v * 1e3 : v * 1e6; }
const char* unit(Dimension d) { return d == Dimension::Length ? "um" : "urad"; }

py::dict runDict(const Machine& m, const MeasurementRun& r) {
  py::array_t<double> poses({r.poses(), static_cast<Eigen::Index>(m.commandedCount())});
  auto w = poses.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < r.poses(); ++i)
    for (int j = 0; j < m.commandedCount(); ++j)
      w(i, j) = m.axes[static_cast<size_t>(j)].isRotary() ? r.q(i, j) / kDeg : r.q(i, j);
  py::array_t<double> readings({r.readings.rows(), r.readings.cols()});
  auto rw = readings.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < r.readings.rows(); ++i)
    for (Eigen::Index k = 0; k < r.readings.cols(); ++k) rw(i, k) = r.readings(i, k) * 1e3;
  std::vector<double> angle;
  for (double a : r.angle) angle.push_back(a / kDeg);
  return py::dict(py::arg("name") = r.name, py::arg("instrument") = instrumentName(r.instrument), py::arg("poses") = poses,
                  py::arg("readings_um") = readings, py::arg("angle_deg") = angle, py::arg("sense") = r.sense,
                  py::arg("length_mm") = r.setup.length);
}

py::dict observabilityDict(const ObservabilityReport& rep) {
  py::list groups;
  for (const auto& g : rep.groups) groups.append(py::dict(py::arg("parameters") = g.names, py::arg("observable") = g.observable));
  return py::dict(py::arg("names") = rep.names,
                  py::arg("singular_values") = std::vector<double>(rep.singularValues.data(),
                                                                   rep.singularValues.data() + rep.singularValues.size()),
                  py::arg("rank") = rep.rank, py::arg("condition") = rep.condition,
                  py::arg("identifiable") = rep.identifiable(), py::arg("no_effect") = rep.noEffect,
                  py::arg("groups") = groups, py::arg("findings") = rep.findings());
}

IdentificationProblem problemFor(PyMachine& m, std::vector<MeasurementRun> runs, const std::vector<std::string>& params) {
  IdentificationProblem p;
  p.machine = m.shared();
  p.start = m.errors();
  p.runs = std::move(runs);
  for (const auto& n : params) {
    try {
      p.parameters.push_back(findParameter(m.machine(), m.errors(), n));
    } catch (const std::invalid_argument& e) {
      throw InputError(InputLocation{"", 0, n}, e.what());
    }
  }
  return p;
}

}  // namespace

void bindMeasurement(py::class_<PyMachine>& cls) {
  cls.def(
         "simulate",
         [](PyMachine& m, const std::string& plan, double noiseUm, unsigned seed, const std::string& outputDir) {
           const auto nominal = compileNominal(m.shared());
           const auto model = compile(m.shared(), m.errors());
           auto runs = loadTestPlan(nominal, plan).runs;
           std::mt19937_64 rng(seed);
           py::list out;
           std::vector<std::pair<std::string, std::string>> files;
           for (auto& r : runs) {
             simulateRun(model, nominal, r, {}, noiseUm * 1e-3, &rng);
             if (!outputDir.empty())
               files.emplace_back((std::filesystem::path(outputDir) / (r.name + ".csv")).string(), measurementCsv(m.machine(), r));
             out.append(runDict(m.machine(), r));
           }
           if (!outputDir.empty()) std::filesystem::create_directories(outputDir);
           for (const auto& [path, text] : files) writeFileAtomically(path, text);
           return out;
         },
         py::arg("plan"), py::arg("noise_um") = 0.0, py::arg("seed") = 1, py::arg("output_dir") = "",
         "Every run of a test plan simulated on this machine (optionally written as CSV files)")
      .def(
          "read_measurement",
          [](PyMachine& m, const std::string& path) { return runDict(m.machine(), readMeasurementCsv(compileNominal(m.shared()), path)); },
          py::arg("path"), "A measurement CSV file (docs/file-formats.md)")
      .def(
          "evaluate_ballbar",
          [](PyMachine& m, const std::string& path) {
            const auto run = readMeasurementCsv(compileNominal(m.shared()), path);
            CircularTestResult r;
            try {
              r = evaluateCircularTest(run);
            } catch (const std::invalid_argument& e) {
              throw InputError(InputLocation{path, 0, ""}, e.what());
            }
            py::list directions;
            for (const auto& d : r.directions)
              directions.append(py::dict(py::arg("sense") = d.sense, py::arg("circular_deviation_um") = d.circularDeviation * 1e3,
                                         py::arg("radial_min_um") = d.radialMin * 1e3, py::arg("radial_max_um") = d.radialMax * 1e3));
            const auto& g = r.diagnostics;
            const Vec3 e = r.eccentricity.eccentricity;
            auto out = runDict(m.machine(), run);
            out["eccentricity_um"] = std::vector<double>{e.x() * 1e3, e.y() * 1e3, e.z() * 1e3};
            out["eccentricity_plot_um"] = std::vector<double>{r.eccentricity.e1 * 1e3, r.eccentricity.e2 * 1e3};
            out["offset_um"] = r.eccentricity.offset * 1e3;
            out["directions"] = directions;
            out["hysteresis_um"] = r.bothDirections ? py::object(py::float_(r.hysteresis * 1e3)) : py::object(py::none());
            out["diagnostics"] = py::dict(
                py::arg("squareness_urad") = g.squareness * 1e6, py::arg("scale_mismatch_um_per_m") = g.scaleMismatch * 1e6,
                py::arg("servo_mismatch_ms") = g.servoMismatch * 1e3, py::arg("backlash_a_um") = g.backlashA * 1e3,
                py::arg("backlash_b_um") = g.backlashB * 1e3, py::arg("reversal_spike_a_um") = g.reversalSpikeA * 1e3,
                py::arg("reversal_spike_b_um") = g.reversalSpikeB * 1e3, py::arg("residual_rms_um") = g.residualRms * 1e3);
            return out;
          },
          py::arg("path"), "ISO 230-4 evaluation, eccentricity and diagnostics of a ballbar CSV file")
      .def(
          "observability",
          [](PyMachine& m, const std::string& plan, std::vector<std::string> params) {
            auto p = loadTestPlan(compileNominal(m.shared()), plan);
            if (params.empty()) params = p.parameters;
            return observabilityDict(planObservability(problemFor(m, std::move(p.runs), params), 0));
          },
          py::arg("plan"), py::arg("parameters") = std::vector<std::string>{},
          "Which parameters a test plan determines (defaults: the plan's own list)")
      .def(
          "identify",
          [](PyMachine& m, const std::vector<std::string>& files, const std::vector<std::string>& params, bool robust) {
            const auto nominal = compileNominal(m.shared());
            std::vector<MeasurementRun> runs;
            for (const auto& f : files) runs.push_back(readMeasurementCsv(nominal, f));
            auto problem = problemFor(m, std::move(runs), params);
            IdentificationOptions o;
            o.robust = robust;
            o.threads = 0;
            IdentificationResult r;
            try {
              py::gil_scoped_release release;
              r = identify(problem, o);
            } catch (const NotIdentifiable& e) {
              throw InputError(InputLocation{"", 0, "parameters"}, std::string("refused: ") + e.what());
            } catch (const std::invalid_argument& e) {
              throw InputError(InputLocation{"", 0, "files"}, e.what());
            }
            std::vector<double> values, uncertainty;
            std::vector<std::string> units;
            for (Eigen::Index k = 0; k < r.values.size(); ++k) {
              const auto d = r.columns.dimensions[static_cast<size_t>(k)];
              values.push_back(display(r.values[k], d));
              uncertainty.push_back(display(r.uncertainty[k], d));
              units.push_back(unit(d));
            }
            return py::dict(py::arg("names") = r.columns.names, py::arg("values") = values,
                            py::arg("uncertainty") = uncertainty, py::arg("units") = units,
                            py::arg("sigma_um") = r.sigma * 1e3, py::arg("residual_rms_um") = r.residualRms * 1e3,
                            py::arg("residual_max_um") = r.residualMax * 1e3, py::arg("iterations") = r.iterations,
                            py::arg("converged") = r.converged, py::arg("observability") = observabilityDict(r.observability));
          },
          py::arg("files"), py::arg("parameters"), py::arg("robust") = false,
          "Least-squares estimates with standard uncertainties from measurement CSV files");
}

}  // namespace mtacc::python
