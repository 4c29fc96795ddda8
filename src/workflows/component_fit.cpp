#include "mtacc/workflows/component_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {
namespace {

[[noreturn]] void fail(const std::string& key, const std::string& what) { throw InputError(InputLocation{"", 0, key}, what); }

std::vector<double> chooseBreaks(const Axis& axis, const std::vector<double>& positions, const ComponentFitRequest& r) {
  const double lo = positions.front(), hi = positions.back();
  if (!r.breaks.empty()) {
    std::vector<double> b;
    for (const double v : r.breaks) b.push_back(v * (axis.isRotary() ? kDeg : 1.0));
    for (size_t i = 1; i < b.size(); ++i)
      if (!(b[i] > b[i - 1])) fail("breaks", "the breaks must increase strictly");
    if (b.size() < 2) fail("breaks", "give at least the two ends of the range");
    if (axis.travel && (b.front() < axis.travel->min - 1e-9 || b.back() > axis.travel->max + 1e-9))
      fail("breaks", "a break outside the travel of " + axis.name);
    if (b.front() > lo + 1e-9 || b.back() < hi - 1e-9)
      fail("breaks", "the breaks must span the measured positions (from the first to the last)");
    return b;
  }
  if (r.pieces > 10000) fail("pieces", "at most 10000 pieces");
  return evenBreaks(lo, hi, axis.isRotary(), positions.size(), r.degree, r.pieces);
}

}  // namespace

const OptionSchema& componentSimulationSchema() {
  static const OptionSchema schema{
      "simulate component",
      {{.key = "component", .kind = OptionKind::Text, .help = "component error: the 1991 BCR report name (xrx, ztz, ...) or ISO (EAX, EZZ)",
        .required = true},
       {.key = "output", .kind = OptionKind::Text, .help = "CSV to write (atomically)", .required = true},
       {"step", OptionKind::Number, "step between positions over the travel (mm or deg)", "10"},
       {"runs", OptionKind::Count, "runs, each forward and backward", "20"},
       {"noise", OptionKind::Text, "standard deviation of one reading, e.g. 0.5arcsec or 0.2um; default none"},
       {"abbe_offset", OptionKind::Text, "measuring point relative to the carriage centroid, e.g. 0,60,110mm (translations)"},
       {"instrument", OptionKind::Text, "instrument named in the file (e.g. levels, laser)"},
       {"reading_time", OptionKind::Number, "seconds per reading", "6"},
       {"disturbance", OptionKind::Text, "a periodic disturbance of one reading, e.g. 1.5arcsec (the lubrication pump)"},
       {"disturbance_interval", OptionKind::Number, "seconds between disturbances", "1800"},
       {"settling", OptionKind::Text, "a drift at the start that dies away, e.g. 2arcsec (the machine settling)"},
       {"settling_time", OptionKind::Number, "seconds: the settling drift's time constant", "600"},
       {.key = "seed", .kind = OptionKind::Count, .help = "random seed", .defaultText = "1", .low = 0, .high = 2147483647,
        .outOfRange = "must be from 0 to 2147483647"}}};
  return schema;
}

ComponentSimulationRequest componentSimulationRequest(const OptionValues& values) {
  const OptionReader read(componentSimulationSchema(), values);
  ComponentSimulationRequest r;
  r.component = *read.text("component");
  r.output = *read.text("output");
  r.step = *read.number("step");
  r.runs = *read.count("runs");
  r.noise = read.text("noise").value_or("");
  if (const auto abbe = read.text("abbe_offset")) r.abbeOffset = parseLengths(*abbe, "abbe_offset");
  r.instrument = read.text("instrument").value_or("");
  r.readingTime = *read.number("reading_time");
  r.disturbance = read.text("disturbance").value_or("");
  r.disturbanceInterval = *read.number("disturbance_interval");
  r.settling = read.text("settling").value_or("");
  r.settlingTime = *read.number("settling_time");
  r.seed = static_cast<std::uint64_t>(*read.count("seed"));
  return r;
}

const OptionSchema& componentFitSchema() {
  static const OptionSchema schema{
      "fit",
      {{.key = "data", .kind = OptionKind::Text, .help = "Component runs CSV (docs/file-formats.md \"Component runs\")", .positional = true},
       {"breaks", OptionKind::List, "Fixed breaks in the axis unit (mm or deg), e.g. 0,50,100,200; default: pieces"},
       {.key = "pieces", .kind = OptionKind::Count, .help = "Equal intervals over the measured range (0: about 100 mm or 30 deg each)",
        .defaultText = "0", .low = 0, .high = 10000, .outOfRange = "must be from 0 (about 100 mm or 30 deg each) to 10000"},
       {.key = "degree", .kind = OptionKind::Count, .help = "1 (piecewise linear) or 2 (C1 piecewise quadratic)", .defaultText = "2", .low = 1,
        .high = 2, .outOfRange = "1 (piecewise linear) or 2 (C1 piecewise quadratic)"},
       {.key = "significance", .kind = OptionKind::Number, .help = "Stepwise removal level of the t-test (0 keeps every term)",
        .defaultText = "0.05"},
       {"period", OptionKind::Number, "A periodic term of this wavelength (axis unit), fitted with the trend"},
       {.key = "period_zero", .kind = OptionKind::Number, .help = "Position where the periodic term starts (axis unit)", .defaultText = "0"},
       {.key = "disturbance_threshold", .kind = OptionKind::Number, .help = "Flag readings beyond this many robust standard deviations",
        .defaultText = "5"},
       {"remove_disturbed", OptionKind::Flag, "Leave the flagged readings out of the means"}}};
  return schema;
}

ComponentFitRequest componentFitRequest(const OptionValues& values) {
  const OptionReader read(componentFitSchema(), values);
  ComponentFitRequest r;
  r.file = *read.text("data");
  for (const auto& b : read.list("breaks")) r.breaks.push_back(parseNumber(b, "breaks"));
  r.pieces = *read.count("pieces");
  r.degree = *read.count("degree");
  r.significance = *read.number("significance");
  r.period = read.number("period");
  r.periodZero = *read.number("period_zero");
  r.disturbanceThreshold = *read.number("disturbance_threshold");
  r.removeDisturbed = read.flag("remove_disturbed");
  return r;
}

ComponentFitStudy fitComponentFile(const MachineSetup& setup, const ComponentFitRequest& r) {
  if (r.degree != 1 && r.degree != 2) fail("degree", "1 (piecewise linear) or 2 (C1 piecewise quadratic, seed 003)");
  if (!(r.significance >= 0.0 && r.significance < 1.0)) fail("significance", "a probability from 0 (keep every term) to below 1");
  ComponentFitStudy s;
  s.machine = setup.machine;
  s.data = readComponentRuns(*setup.machine, r.file);
  auto& runs = s.data.runs;
  const Axis& axis = setup.machine->axes[static_cast<size_t>(s.data.component.axis)];
  const int component = s.data.component.component;
  if (s.data.expansion) {
    const double x0 = runs.positions.front();
    for (auto [values, temperatures] : {std::pair{&runs.forward, &s.data.forwardTemperature}, std::pair{&runs.backward, &s.data.backwardTemperature}})
      for (Eigen::Index i = 0; i < values->rows(); ++i)
        for (Eigen::Index j = 0; j < values->cols(); ++j)
          (*values)(i, j) = scaleTemperatureCorrected((*values)(i, j), runs.positions[static_cast<size_t>(i)], x0, (*temperatures)(i, j),
                                                      s.data.referenceTemperature, *s.data.expansion);
    s.corrections.push_back(fmt::format("scale temperature: alpha = {:g}/K, referred to {:g} deg C, zero at {:g}", *s.data.expansion,
                                        s.data.referenceTemperature, x0));
  }
  if (s.data.abbeOffset) {
    const auto& motion = setup.errors.axes[static_cast<size_t>(s.data.component.axis)].motion;
    if (motion[3].empty() && motion[4].empty() && motion[5].empty())
      throw InputError(InputLocation{r.file, 0, "abbe_offset"},
                       "the Abbe correction needs the rotation errors of " + axis.name + " (EA, EB, EC" + axis.name +
                           "): give an errors file with them");
    for (Eigen::Index i = 0; i < runs.forward.rows(); ++i) {
      const double x = runs.positions[static_cast<size_t>(i)];
      const Vec3 rotation(motion[3].value(x, 0), motion[4].value(x, 0), motion[5].value(x, 0));
      const double shift = abbeCorrected(0.0, rotation, *s.data.abbeOffset, component);
      runs.forward.row(i).array() += shift;
      runs.backward.row(i).array() += shift;
    }
    s.corrections.push_back(fmt::format("Abbe offset ({:g}, {:g}, {:g}) mm with the rotations of {} from the error model",
                                        s.data.abbeOffset->x(), s.data.abbeOffset->y(), s.data.abbeOffset->z(), axis.name));
  }
  s.disturbances = findDisturbances(runs, r.disturbanceThreshold);
  if (r.removeDisturbed && !s.disturbances.readings.empty()) {
    // A flagged reading is replaced by the mean of the other readings at its position and
    // direction, which leaves it out of that mean.
    for (const auto& d : s.disturbances.readings) {
      auto& m = d.forward ? runs.forward : runs.backward;
      const auto i = static_cast<Eigen::Index>(std::lower_bound(runs.positions.begin(), runs.positions.end(), d.position) - runs.positions.begin());
      m(i, d.run) = (m.row(i).sum() - m(i, d.run)) / static_cast<double>(m.cols() - 1);
    }
    s.corrections.push_back(fmt::format("{} disturbed reading(s) left out of the means", s.disturbances.readings.size()));
  }
  if (r.removeDisturbed && !s.disturbances.unsettledRuns.empty()) {
    if (s.disturbances.unsettledRuns.size() + 2 > static_cast<size_t>(runs.forward.cols()))
      throw InputError(InputLocation{r.file, 0, "run"}, fmt::format("{} of the {} runs have not settled: fewer than two would be left",
                                                                     s.disturbances.unsettledRuns.size(), runs.forward.cols()));
    runs = withoutRuns(runs, s.disturbances.unsettledRuns);
    s.corrections.push_back(fmt::format("the first {} run(s), not yet settled, left out", s.disturbances.unsettledRuns.size()));
  }
  s.curve = averageRuns(runs);
  ComponentFitOptions o;
  o.breaks = chooseBreaks(axis, runs.positions, r);
  o.degree = r.degree;
  o.significance = r.significance;
  if (r.period) {
    if (!(*r.period > 0.0 && std::isfinite(*r.period))) fail("period", "must be positive");
    const double unit = axis.isRotary() ? kDeg : 1.0;
    o.period = *r.period * unit;
    o.periodZero = r.periodZero * unit;
  }
  const std::vector<double> mean(s.curve.mean.data(), s.curve.mean.data() + s.curve.mean.size());
  try {
    s.fit = fitComponent(runs.positions, mean, o);
  } catch (const InvalidInput& e) {
    fail(r.breaks.empty() ? "pieces" : "breaks",
         std::string(e.what()) + fmt::format(" ({} positions, {} pieces of degree {})", runs.positions.size(), o.breaks.size() - 1, r.degree));
  }
  std::vector<PiecewiseTerm> terms{s.fit.trend};
  if (s.fit.periodic) terms.push_back(*s.fit.periodic);
  s.errors = setup.errors;
  ErrorFunction& fitted = s.errors.axes[static_cast<size_t>(s.data.component.axis)].motion[static_cast<size_t>(component)];
  fitted = ErrorFunction();
  // In the form the errors file keeps (and reads back): every interval's polynomial.
  for (const auto& term : terms) fitted.add(piecewiseFromIntervals(term.breaks, term.intervals(), term.period, term.zero));
  s.yaml = fmt::format("  # fitted by mtacc from {}: {} positions x {} runs each way, residual {:.4g} {}\n", r.file, runs.positions.size(),
                       runs.forward.cols(), toDisplay(s.fit.residualStd, component < 3 ? Dimension::Length : Dimension::Angle),
                       displayUnit(component < 3 ? Dimension::Length : Dimension::Angle)) +
           piecewiseErrorYaml(s.data.componentName, terms, component < 3 ? Dimension::Length : Dimension::Angle,
                              axis.isRotary() ? Dimension::Angle : Dimension::Length);
  return s;
}

ComponentRunsFile simulateComponentFile(const MachineSetup& setup, const ComponentSimulationRequest& r) {
  const auto c = findMotionComponent(*setup.machine, r.component);
  if (!c) fail("component", "'" + r.component + "' is not a component error of this machine (e.g. EXX, xtx, EAX, xrx)");
  const Axis& axis = setup.machine->axes[static_cast<size_t>(c->axis)];
  const Dimension dim = c->component < 3 ? Dimension::Length : Dimension::Angle;
  const double unit = axis.isRotary() ? kDeg : 1.0;
  const double lo = axis.travel ? axis.travel->min : 0.0, hi = axis.travel ? axis.travel->max : 2.0 * kPi - r.step * unit;
  if (!(r.step > 0.0) || (hi - lo) / (r.step * unit) > 100000) fail("step", "a positive step, at most 100000 positions over the travel");
  if (r.runs < 2 || r.runs > 1000) fail("runs", "from 2 to 1000 runs");
  if (!(r.readingTime > 0.0) || !(r.disturbanceInterval > 0.0)) fail("reading-time", "times must be positive");
  if (!(r.settlingTime > 0.0 && r.settlingTime <= 1e9)) fail("settling-time", "seconds, above 0 and at most 1e9");
  if (c->component >= 3 && !r.abbeOffset.isZero()) fail("abbe-offset", "an Abbe offset applies to a translation component");
  ComponentRunsSpec spec;
  for (double x = lo; x <= hi + 1e-9 * std::max(1.0, std::abs(hi)); x += r.step * unit) spec.positions.push_back(std::min(x, hi));
  if (spec.positions.size() < 2) fail("step", "the step leaves fewer than two positions on the travel");
  spec.runs = r.runs;
  spec.noise = r.noise.empty() ? 0.0 : parseQuantityAs(r.noise, dim, "noise");
  if (!(spec.noise >= 0.0)) fail("noise", "must not be negative");
  spec.abbeOffset = r.abbeOffset;
  spec.readingTime = r.readingTime;
  if (!r.disturbance.empty()) spec.disturbanceAmplitude = parseQuantityAs(r.disturbance, dim, "disturbance");
  spec.disturbanceInterval = r.disturbanceInterval;
  if (!r.settling.empty()) spec.settlingOffset = parseQuantityAs(r.settling, dim, "settling");
  spec.settlingTime = r.settlingTime;
  spec.seed = r.seed;
  ComponentRunsFile f;
  f.file = r.output;
  f.componentName = r.component;
  f.component = *c;
  f.instrument = r.instrument;
  if (spec.noise > 0.0) f.uncertainty = spec.noise;
  if (!r.abbeOffset.isZero()) f.abbeOffset = r.abbeOffset;
  f.runs = simulateComponentRuns(setup.errors.axes[static_cast<size_t>(c->axis)], c->component, spec);
  writeFileAtomically(r.output, componentRunsCsv(*setup.machine, f));
  return f;
}

nlohmann::json toJson(const ComponentFitStudy& s) {
  const Dimension dim = s.data.component.component < 3 ? Dimension::Length : Dimension::Angle;
  const Axis& axis = s.machine->axes[static_cast<size_t>(s.data.component.axis)];
  const double pos = axis.isRotary() ? 1.0 / kDeg : 1.0;
  const double val = toDisplay(1.0, dim);
  auto scaled = [](const auto& v, double k) {
    std::vector<double> out;
    for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i] * k);
    return out;
  };
  auto matrix = [&](const Eigen::MatrixXd& m) {
    nlohmann::json out = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.push_back(scaled(m.col(j), val));
    return out;
  };
  const Eigen::Map<const Eigen::VectorXd> positions(s.curve.positions.data(), static_cast<Eigen::Index>(s.curve.positions.size()));
  nlohmann::json j;
  j["file"] = s.data.file;
  j["component"] = s.data.componentName;
  j["iso_name"] = motionErrorName(*s.machine, s.data.component.axis, s.data.component.component);
  j["axis"] = axis.name;
  j["instrument"] = s.data.instrument;
  j["unit"] = displayUnit(dim);
  j["position_unit"] = axis.isRotary() ? "deg" : "mm";
  j["corrections"] = s.corrections;
  j["positions"] = scaled(positions, pos);
  j["runs_forward"] = matrix(s.data.runs.forward);
  j["runs_backward"] = matrix(s.data.runs.backward);
  j["mean"] = scaled(s.curve.mean, val);
  j["mean_forward"] = scaled(s.curve.meanForward, val);
  j["mean_backward"] = scaled(s.curve.meanBackward, val);
  j["scatter"] = scaled(s.curve.scatter, val);
  std::vector<double> fitted, uncertainty, gridX, gridFit, gridU;
  for (const double x : s.curve.positions) {
    fitted.push_back(s.fit.value(x) * val);
    uncertainty.push_back(s.fit.valueUncertainty(x) * val);
  }
  const double lo = s.fit.trend.breaks.front(), hi = s.fit.trend.breaks.back();
  for (int k = 0; k <= 400; ++k) {
    const double x = lo + (hi - lo) * k / 400.0;
    gridX.push_back(x * pos);
    gridFit.push_back(s.fit.value(x) * val);
    gridU.push_back(s.fit.valueUncertainty(x) * val);
  }
  j["fit"] = {{"at_positions", fitted}, {"uncertainty_at_positions", uncertainty}, {"grid", gridX}, {"grid_value", gridFit},
              {"grid_uncertainty", gridU}, {"breaks", scaled(Eigen::Map<const Eigen::VectorXd>(s.fit.trend.breaks.data(), static_cast<Eigen::Index>(s.fit.trend.breaks.size())), pos)},
              {"removed", s.fit.removed}, {"residual_std", s.fit.residualStd * val}, {"degrees_of_freedom", s.fit.degreesOfFreedom},
              {"periodic", s.fit.periodic ? nlohmann::json(s.fit.periodic->period * pos) : nlohmann::json(nullptr)}};
  nlohmann::json flags = nlohmann::json::array();
  for (const auto& d : s.disturbances.readings)
    flags.push_back({{"run", d.run + 1}, {"direction", d.forward ? "forward" : "backward"}, {"position", d.position * pos},
                     {"departure", d.departure * val}, {"time_s", std::isnan(d.time) ? nlohmann::json(nullptr) : nlohmann::json(d.time)}});
  nlohmann::json unsettled = nlohmann::json::array();
  for (int run : s.disturbances.unsettledRuns) unsettled.push_back(run + 1);
  j["disturbances"] = {{"readings", flags},
                       {"interval_s", s.disturbances.interval ? nlohmann::json(*s.disturbances.interval) : nlohmann::json(nullptr)},
                       {"unsettled_runs", unsettled}};
  j["yaml"] = s.yaml;
  return j;
}

}  // namespace mtacc
