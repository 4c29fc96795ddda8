#include "mtacc/workflows/cubic_test.hpp"

#include <fmt/format.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"
#include "mtacc/io/point_cloud.hpp"
#include "mtacc/io/recorded_signal.hpp"

namespace mtacc {
namespace {

HeightMap machinedSurface(const KinematicModel& model, const std::vector<CubicZonePath>& path, const CubicTestSpec& spec,
                          const HeightGrid& grid, const CubicTestRequest& o, size_t* moves = nullptr) {
  const CutterPath cutter = cutterPath(model, path, spec.tool, o.chordTolerance);
  if (moves) *moves = cutter.moves();
  HeightMap map = stockHeightMap(grid, spec.topHeight, spec.depth);
  cutHeightMap(map, cutter, o.threads);
  return map;
}

std::shared_ptr<const Machine> withAlignment(const Machine& m, WorkpieceAlignment alignment) {
  auto copy = std::make_shared<Machine>(m);
  copy->alignment = alignment;
  return copy;
}

std::vector<ZonePlane> perUnit(std::vector<ZonePlane> planes, double step) {
  for (auto& p : planes) {
    p.mean /= step;
    p.slopeX /= step;
    p.slopeY /= step;
    p.residualPeakToValley /= step;
  }
  return planes;
}

HeightMap scaled(HeightMap map, double factor) {
  for (float& h : map.height) h = static_cast<float>(h * factor);
  return map;
}

std::vector<std::string> rotaryLocationErrors(const Machine& m) {
  std::vector<std::string> names;
  for (int a = 0; a < static_cast<int>(m.axes.size()); ++a)
    if (m.axes[static_cast<size_t>(a)].type == AxisType::Rotary)
      for (auto& n : locationErrorNames(m, a)) names.push_back(std::move(n));
  return names;
}

nlohmann::json planeJson(const ZonePlane& p) {
  return {{"mean_um", p.mean * 1e3}, {"slope_x_um_per_mm", p.slopeX * 1e3}, {"slope_y_um_per_mm", p.slopeY * 1e3},
          {"residual_peak_to_valley_um", p.residualPeakToValley * 1e3}, {"cells", p.cells}};
}

}  // namespace

const OptionSchema& cubicTestSchema() {
  static const OptionSchema schema{
      "cubic",
      {{.key = "test", .kind = OptionKind::Text, .help = "Test piece (YAML) or bundled name", .defaultText = "seed001-cubic"},
       {.key = "grid", .kind = OptionKind::Number, .help = "Grid spacing of the simulated surface [mm]", .defaultText = "0.01"},
       {.key = "inset", .kind = OptionKind::Number, .help = "Margin left out along each zone edge when zones are evaluated [mm]",
        .defaultText = "1"},
       {.key = "chord_tolerance", .kind = OptionKind::Number, .help = "Largest departure of the actual path from its chords [mm]",
        .defaultText = "1e-6"},
       {"sensitivities", OptionKind::Flag, "Sensitivity k = E / epsilon of every zone to each error, with and without M_WC (the workpiece "
                                           "aligned with the machine at the reference pose, and fixed to the table)"},
       {"sensitivity_parameters", OptionKind::List, "Errors for the sensitivities (default: the rotary axes' location errors)"},
       {.key = "sensitivity_grid", .kind = OptionKind::Number, .help = "Grid spacing for the sensitivities [mm]", .defaultText = "0.02"},
       threadsOption(),
       {"gcode", OptionKind::Text, "Write the NC program to FILE"},
       {"cl", OptionKind::Text, "Write the CL data (zone, tool tip, tool vector) to FILE.csv"},
       {"map", OptionKind::Text, "Write the deviation map referenced to zone I to FILE.svg (zones, colour bar) or FILE.png"},
       {.key = "map_limit", .kind = OptionKind::Text, .help = "Deviation shown at full colour (as Li et al. 2021 Fig. 16)",
        .defaultText = "10 um"},
       {"heights", OptionKind::Text, "Write the machined heights to FILE.csv (um) or FILE.npy (float32, mm)"},
       {"surface", OptionKind::Text, "Write the machined surface to FILE.ply or FILE.stl (at most 1e6 vertices)"},
       {"zones_out", OptionKind::Text, "Write the zone results (heights and tilts) to FILE.csv, for cubic-identify"},
       {"scan", OptionKind::Text, "A scanned face of the machined block (FILE.csv, .ply or .stl, mm, workpiece frame), evaluated beside the simulation"},
       {.key = "scan_grid", .kind = OptionKind::Number, .help = "Cell size over which the scanned points are fitted [mm]", .defaultText = "0.5"},
       {"scan_zones_out", OptionKind::Text, "Write the scanned zone results to FILE.csv, for cubic-identify"},
       {"trace", OptionKind::Text, "The axes' actual positions recorded during the cut (CSV or .npy: time_s and one column per axis, mm and deg), "
                                   "machined beside the programmed path (Li et al. 2021 eqs 13-14)"},
       {"trace_cl", OptionKind::Text, "Write the CL data of the recorded positions (tool tip and vector, eqs 13-14) to FILE.csv"}}};
  return schema;
}

CubicTestRequest cubicTestRequest(const OptionValues& values) {
  const OptionReader read(cubicTestSchema(), values);
  CubicTestRequest r;
  r.spec = loadCubicTest(*read.text("test"));
  r.gridSpacing = *read.number("grid");
  r.inset = *read.number("inset");
  r.chordTolerance = *read.number("chord_tolerance");
  r.sensitivities = read.flag("sensitivities");
  r.sensitivityParameters = read.list("sensitivity_parameters");
  r.sensitivityGrid = *read.number("sensitivity_grid");
  r.threads = *read.count("threads");
  r.scanFile = read.text("scan").value_or("");
  r.scanGrid = *read.number("scan_grid");
  r.traceFile = read.text("trace").value_or("");
  return r;
}

JointMatrix readAxisTrace(const Machine& machine, const std::string& path) {
  SignalLayout layout;
  for (int a = 0; a < machine.commandedCount(); ++a) layout.channels.push_back(machine.axes[static_cast<size_t>(a)].name);
  layout.minimumSamples = 2;
  const auto signal = readRecordedSignal(path, layout);
  const auto& c = signal.trace.channels;
  JointMatrix q(static_cast<Eigen::Index>(signal.trace.samples()), machine.commandedCount());
  for (int a = 0; a < machine.commandedCount(); ++a) {
    const double unit = machine.axes[static_cast<size_t>(a)].isRotary() ? kDeg : 1.0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) q(i, a) = c[static_cast<size_t>(a)][static_cast<size_t>(i)] * unit;
  }
  return q;
}

std::string traceClCsv(const TracedCubicTest& trace) {
  std::string out = "run,x,y,z,i,j,k\n";
  for (size_t r = 0; r < trace.cl.size(); ++r)
    for (const auto& t : trace.cl[r]) {
      out += fmt::format("{},{:.9f},{:.9f},{:.9f},{:.12f},{:.12f},{:.12f}\n", r + 1, t.position.x(), t.position.y(), t.position.z(),
                         t.direction.x(), t.direction.y(), t.direction.z());
    }
  return out;
}

ScannedCubicTest scannedCubicTest(const std::vector<Vec3>& points, const CubicTestSpec& spec, double gridSpacing, double inset,
                                  size_t referenceZone, const std::string& file) {
  ScannedCubicTest s;
  s.points = points.size();
  s.map = scannedHeightMap(points, squareGrid(spec.blockSize, gridSpacing, "scan_grid", spec.centreX, spec.centreY), spec.topHeight);
  try {
    s.zones = referencedToZone(zonePlanes(s.map, spec, inset), spec, referenceZone);
  } catch (const InvalidInput& e) {
    throw InputError(InputLocation{file, 0, "points"}, std::string("the scan does not cover the zones: ") + e.what());
  }
  return s;
}

CubicTestStudy cubicTestStudy(const MachineSetup& setup, const CubicTestRequest& options) {
  const auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw InputError(InputLocation{"", 0, key}, what);
  };
  if (const auto p = cubicTestSpecProblem(options.spec)) throw InputError(InputLocation{"", 0, "test." + p->key}, p->what);
  require(options.chordTolerance >= 1e-9 && options.chordTolerance <= 1, "chord_tolerance", "must be in [1e-9, 1] mm");
  require(options.inset >= 0 && options.inset < options.spec.zoneSize / 2, "inset", "must be in [0, half the zone size)");
  require(options.lengthStep > 0 && options.lengthStep <= 1, "length_step", "must be in (0, 1] mm");
  require(options.angleStep > 0 && options.angleStep <= 0.02, "angle_step", "must be in (0, 0.02] rad");
  require(options.threads >= 0 && options.threads <= 1024, "threads", "must be from 0 (every core) to 1024");
  require(options.scanGrid >= 0.01 && options.scanGrid <= options.spec.zoneSize / 4, "scan_grid", "must be from 0.01 mm to a quarter of the zone size");
  const auto progress = [&](const std::string& stage) {
    if (options.progress) options.progress(stage);
  };
  // The scan is read first: a file that cannot be read fails before the machining.
  const std::vector<Vec3> scanPoints = options.scanFile.empty() ? std::vector<Vec3>{} : readPointCloud(options.scanFile);
  const JointMatrix trace = options.traceFile.empty() ? JointMatrix{} : readAxisTrace(*setup.machine, options.traceFile);
  const auto traceRuns = recordedCuttingRuns(*setup.machine, trace);
  if (!options.traceFile.empty() && traceRuns.empty())
    throw InputError(InputLocation{options.traceFile, 0, "time_s"}, "no run of samples with the rotary axes clamped");
  CubicTestStudy s;
  s.machine = setup.machine;
  s.options = options;
  const CubicTestSpec& spec = options.spec;
  const auto nominal = setup.nominal();
  try {
    s.path = cubicToolPath(nominal, spec);
  } catch (const UnreachablePose& e) {
    throw UnreachableInput(InputLocation{"", 0, "test"}, std::string("the test cannot be machined: ") + e.what());
  }
  s.referenceZone = referenceZone(spec);
  const HeightGrid grid = squareGrid(spec.blockSize, options.gridSpacing, "grid", spec.centreX, spec.centreY);
  progress(fmt::format("machining the error-free surface ({} x {} cells)", grid.nx, grid.ny));
  s.nominal = machinedSurface(nominal, s.path, spec, grid, options);
  progress("machining the surface with the machine's errors");
  s.actual = machinedSurface(setup.actual(), s.path, spec, grid, options, &s.cutterMoves);
  const auto deviation = zonePlanes(s.actual, spec, options.inset, &s.nominal);
  const auto measured = referencedToZone(zonePlanes(s.actual, spec, options.inset), spec, s.referenceZone);
  for (size_t k = 0; k < spec.zones.size(); ++k)
    s.zones.push_back({spec.zones[k].name, s.path[k].clamped, deviation[k], measured[k]});
  if (!options.traceFile.empty()) {
    progress("machining the surface along the recorded axis positions");
    TracedCubicTest t;
    t.samples = static_cast<size_t>(trace.rows());
    t.runs = traceRuns;
    for (const auto& run : t.runs) t.cuttingSamples += static_cast<size_t>(run.q.rows());
    const auto actual = setup.actual();
    for (const auto& run : t.runs) {
      t.cl.emplace_back();
      for (Eigen::Index i = 0; i < run.q.rows(); ++i) t.cl.back().push_back(toolPoint(actual, run.q.row(i).data(), run.direction.row(i).data()));
    }
    t.map = machinedSurface(actual, t.runs, spec, grid, options);
    t.zones = referencedToZone(zonePlanes(t.map, spec, options.inset), spec, s.referenceZone);
    s.trace = std::move(t);
  }
  if (!options.scanFile.empty()) {
    progress("evaluating the scanned face");
    s.scan = scannedCubicTest(scanPoints, spec, options.scanGrid, options.inset, s.referenceZone, options.scanFile);
  }
  if (!options.sensitivities) return s;

  const auto names = options.sensitivityParameters.empty() ? rotaryLocationErrors(*setup.machine) : options.sensitivityParameters;
  const auto parameters = findParameters(setup, names, {"", 0, "sensitivity_parameters"});
  const HeightGrid coarse = squareGrid(spec.blockSize, options.sensitivityGrid, "sensitivity_grid", spec.centreX, spec.centreY);
  const auto coarseNominal = machinedSurface(nominal, s.path, spec, coarse, options);
  const auto onTable = withAlignment(*setup.machine, WorkpieceAlignment::Table);
  const auto aligned = withAlignment(*setup.machine, WorkpieceAlignment::Machine);
  const ErrorModel zero = ErrorModel::zero(*setup.machine);
  for (size_t k = 0; k < parameters.size(); ++k) {
    progress(fmt::format("sensitivity {}/{}: {}", k + 1, parameters.size(), names[k]));
    CubicSensitivity c;
    c.name = names[k];
    c.dimension = parameters[k].dimension;
    c.step = c.dimension == Dimension::Length ? options.lengthStep : options.angleStep;
    // The step is in the unit of the name as given (an alias may count the other way round).
    const ErrorModel single = singleError(*setup.machine, zero, parameters[k], isoSign(names[k]) * c.step);
    for (const auto& [machine, planes, map] : {std::tuple{aligned, &c.withAlignment, &c.mapWithAlignment},
                                               std::tuple{onTable, &c.onTable, &c.mapOnTable}}) {
      const auto e = heightDifference(machinedSurface(compile(machine, single), s.path, spec, coarse, options), coarseNominal);
      *planes = perUnit(zonePlanes(e, spec, options.inset), c.step);
      *map = scaled(e, 1 / c.step);
    }
    s.sensitivities.push_back(std::move(c));
  }
  return s;
}

HeightMap referencedDeviation(const CubicTestStudy& s) {
  HeightMap e = heightDifference(s.actual, s.nominal);
  const auto& spec = s.options.spec;
  const ZonePlane plane = zonePlanes(s.actual, spec, s.options.inset, &s.nominal)[s.referenceZone];
  const CubicZone& zone = spec.zones[s.referenceZone];
  for (int j = 0; j < e.grid.ny; ++j)
    for (int i = 0; i < e.grid.nx; ++i)
      e.height[static_cast<size_t>(j) * static_cast<size_t>(e.grid.nx) + static_cast<size_t>(i)] -=
          static_cast<float>(plane.at(e.grid.x(i) - zone.x, e.grid.y(j) - zone.y));
  return e;
}

nlohmann::json toJson(const CubicTestStudy& s) {
  const Machine& m = *s.machine;
  const CubicTestSpec& spec = s.options.spec;
  nlohmann::json zones = nlohmann::json::array();
  for (size_t k = 0; k < s.zones.size(); ++k) {
    const auto& z = s.zones[k];
    zones.push_back({{"name", z.name},
                     {"centre_mm", {spec.zones[k].x, spec.zones[k].y}},
                     {"tool_vector", vectorJson(spec.zones[k].toolVector)},
                     {"axes", poseJson(m, z.clamped.data())},
                     {"deviation", planeJson(z.deviation)},
                     {"measured", planeJson(z.measured)}});
  }
  nlohmann::json j = {{"machine", m.name},
                      {"alignment", m.alignment == WorkpieceAlignment::Machine ? "machine" : "table"},
                      {"block_mm", spec.blockSize},
                      {"block_centre_mm", {spec.centreX, spec.centreY}},
                      {"zone_size_mm", spec.zoneSize},
                      {"top_mm", spec.topHeight},
                      {"tool", {{"shape", spec.tool.shape == ToolShape::Ball ? "ball" : "flat"}, {"radius_mm", spec.tool.radius}}},
                      {"pick_mm", spec.pick},
                      {"depth_mm", spec.depth},
                      {"feed_mm_per_min", spec.feed},
                      {"grid_mm", s.actual.grid.spacing},
                      {"cells", s.actual.grid.cells()},
                      {"cutter_moves", s.cutterMoves},
                      {"inset_mm", s.options.inset},
                      {"reference_zone", spec.zones[s.referenceZone].name},
                      {"zones", zones}};
  if (s.trace) {
    nlohmann::json traced = nlohmann::json::array();
    for (size_t k = 0; k < s.trace->zones.size(); ++k)
      traced.push_back({{"name", spec.zones[k].name},
                        {"traced", planeJson(s.trace->zones[k])},
                        {"programmed_mean_um", s.zones[k].measured.mean * 1e3},
                        {"difference_um", (s.trace->zones[k].mean - s.zones[k].measured.mean) * 1e3}});
    j["trace"] = {{"file", s.options.traceFile}, {"samples", s.trace->samples}, {"cutting_samples", s.trace->cuttingSamples},
                  {"runs", s.trace->runs.size()}, {"zones", traced}};
  }
  if (s.scan) {
    nlohmann::json scanned = nlohmann::json::array();
    for (size_t k = 0; k < s.scan->zones.size(); ++k)
      scanned.push_back({{"name", spec.zones[k].name},
                         {"scanned", planeJson(s.scan->zones[k])},
                         {"simulated_mean_um", s.zones[k].measured.mean * 1e3},
                         {"difference_um", (s.scan->zones[k].mean - s.zones[k].measured.mean) * 1e3}});
    j["scan"] = {{"file", s.options.scanFile}, {"points", s.scan->points}, {"grid_mm", s.options.scanGrid},
                 {"filled_cells", filledCells(s.scan->map)}, {"cells", s.scan->map.grid.cells()}, {"zones", scanned}};
  }
  if (!s.sensitivities.empty()) {
    nlohmann::json k = nlohmann::json::array();
    for (const auto& c : s.sensitivities) {
      const auto values = [](const std::vector<ZonePlane>& planes) {
        nlohmann::json a = nlohmann::json::array();
        for (const auto& p : planes) a.push_back({{"k", p.mean}, {"slope_x", p.slopeX}, {"slope_y", p.slopeY}});
        return a;
      };
      k.push_back({{"parameter", c.name},
                   {"unit", c.dimension == Dimension::Length ? "mm/mm" : "mm/rad"},
                   {"step", c.step},
                   {"with_alignment", values(c.withAlignment)},
                   {"on_table", values(c.onTable)}});
    }
    j["sensitivities"] = k;
  }
  return j;
}

}  // namespace mtacc
