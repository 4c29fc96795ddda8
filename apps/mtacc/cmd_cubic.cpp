// mtacc cubic MACHINE: Li et al. 2021's cubic machining test — NC program and CL data, the machined
// surface simulated from the erroneous tool path, zone heights and tilts, sensitivities with
// and without M_WC. mtacc cubic-identify MACHINE --zones FILE: the errors from zone results.
#include <fmt/format.h>
#include <unistd.h>

#include <iostream>

#include "cli_common.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/workflows/cubic_identification.hpp"
#include "mtacc/workflows/test_piece_files.hpp"

namespace mtacc::cli {
namespace {

struct CubicCliOptions : MachineOptions {
  OptionValues values;
};

std::string planRow(const ZonePlane& p) {
  return fmt::format("{:>9.3f} {:>8.4f} {:>8.4f}", p.mean * 1e3, p.slopeX * 1e3, p.slopeY * 1e3);
}

void run(const CubicCliOptions& o) {
  const CubicTestFiles files = cubicTestFiles(o.values);
  checkCubicTestFiles(files);
  CubicTestRequest options = cubicTestRequest(o.values);
  const auto setup = loadMachineSetup(o.source);
  const Machine& m = *setup.machine;
  const bool tty = !o.json && isatty(2);
  options.progress = [tty](const std::string& stage) {
    if (tty) std::cerr << "cubic: " << stage << "\n";
  };
  const auto s = cubicTestStudy(setup, options);
  const CubicTestSpec& spec = s.options.spec;
  std::string human = fmt::format(
      "Cubic machining test on {} ({} workpiece): {:g} mm block, {} zones of {:g} mm, {} end R{:g} mm, pick {:g} mm, "
      "depth {:g} mm\nsurface: {} x {} cells of {:g} mm, {} tool moves; zones evaluated {:g} mm inside their edges\n\n",
      m.name, m.alignment == WorkpieceAlignment::Machine ? "aligned (M_WC)" : "on the table", spec.blockSize, spec.zones.size(),
      spec.zoneSize, spec.tool.shape == ToolShape::Ball ? "ball" : "flat", spec.tool.radius, spec.pick, spec.depth,
      s.actual.grid.nx, s.actual.grid.ny, s.actual.grid.spacing, s.cutterMoves, options.inset);
  human += fmt::format("{:<7} {}  {:>27}  {:>27}\n{:<7} {}  {:>9} {:>8} {:>8}  {:>9} {:>8} {:>8}\n", "", poseHeader(m),
                       "deviation E (um, um/mm)", fmt::format("referenced to {} (um)", spec.zones[s.referenceZone].name), "zone",
                       std::string(poseHeader(m).size(), ' '), "mean", "slope x", "slope y", "mean", "slope x", "slope y");
  std::string csv = "zone," + poseCsvHeader(m) + "deviation_um,deviation_slope_x_um_per_mm,deviation_slope_y_um_per_mm,"
                    "measured_um,measured_slope_x_um_per_mm,measured_slope_y_um_per_mm\n";
  for (const auto& z : s.zones) {
    human += fmt::format("{:<7} {}  {}  {}\n", z.name, formatPose(m, z.clamped.data()), planRow(z.deviation), planRow(z.measured));
    csv += fmt::format("{},{}{},{},{},{},{},{}\n", z.name, poseCsv(m, z.clamped.data()), z.deviation.mean * 1e3,
                       z.deviation.slopeX * 1e3, z.deviation.slopeY * 1e3, z.measured.mean * 1e3, z.measured.slopeX * 1e3,
                       z.measured.slopeY * 1e3);
  }
  for (const auto& c : s.sensitivities) {
    const bool length = c.dimension == Dimension::Length;
    human += fmt::format("\nsensitivity k = E / {} ({}, from {} = {:g} {}), per zone: with M_WC | on the table\n", c.name,
                         length ? "mm/mm" : "mm/rad", c.name, length ? c.step * 1e3 : c.step / kDeg, length ? "um" : "deg");
    for (size_t k = 0; k < c.withAlignment.size(); ++k)
      human += fmt::format("  {:<7} {:>9.4f} | {:>9.4f}\n", spec.zones[k].name, c.withAlignment[k].mean, c.onTable[k].mean);
  }
  if (s.scan) {
    human += fmt::format("\nscanned face ({}): {} points, {} of {} cells of {:g} mm with a height; zones referenced to {}\n",
                         s.options.scanFile, s.scan->points, filledCells(s.scan->map), s.scan->map.grid.cells(), s.options.scanGrid,
                         spec.zones[s.referenceZone].name);
    human += fmt::format("  {:<7} {:>12} {:>12} {:>12}\n", "zone", "scanned um", "simulated um", "difference");
    for (size_t k = 0; k < s.scan->zones.size(); ++k)
      human += fmt::format("  {:<7} {:>12.3f} {:>12.3f} {:>12.3f}\n", spec.zones[k].name, s.scan->zones[k].mean * 1e3,
                           s.zones[k].measured.mean * 1e3, (s.scan->zones[k].mean - s.zones[k].measured.mean) * 1e3);
  }
  for (const auto& line : writeCubicTestFiles(s, files)) human += "\n" + line;
  if (human.back() != '\n') human += "\n";
  emit(o, toJson(s), human, csv);
}

struct CubicIdentifyCliOptions : MachineOptions {
  OptionValues values;
  std::string errorsOut;
  bool strict = false;
};

void identify(const CubicIdentifyCliOptions& o) {
  emitIdentification(o, identifyFromZones(loadMachineSetup(o.source), cubicIdentificationRequest(o.values)), o.strict, o.errorsOut);
}

}  // namespace

void addCubicCommands(const CommandLine& app) {
  auto o = std::make_shared<CubicCliOptions>();
  auto cmd = app.subcommand("cubic", "cubic machining test (Li et al. 2021): NC program, machined surface, zone heights, sensitivities");
  cmd.machineOptions(*o);
  cmd.schemaOptions(cubicTestSchema(), o->values);
  cmd.callback([o] { run(*o); });

  auto id = std::make_shared<CubicIdentifyCliOptions>();
  auto idc = app.subcommand("cubic-identify", "errors from the zone results of a cubic machining test (Li et al. 2021 §7.3)");
  idc.machineOptions(*id);
  idc.schemaOptions(cubicIdentificationSchema(), id->values, {{"parameters", "--params"}});
  idc.flag("--strict", id->strict, "exit with status 4 when the fit or the conditioning draws a warning");
  addErrorsOutOption(idc, id->errorsOut);
  idc.callback([id] { identify(*id); });
}

}  // namespace mtacc::cli
