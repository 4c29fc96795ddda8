// mtacc compensate MACHINE --tables DIR: the correction grid, its one-axis functions and the
// controllers' files (Siemens, HEIDENHAIN, LinuxCNC, TwinCAT/ISG), with the residual each leaves;
// with --thermal STATE --every SECONDS rewritten for the state as it is each period.
#include <fmt/chrono.h>
#include <fmt/format.h>

#include <csignal>
#include <ctime>
#include <iostream>

#include "cmd_compensate.hpp"
#include "mtacc/core/input_error.hpp"

namespace mtacc::cli {
namespace {

std::string folderOf(const CompensateOptions& o) { return *OptionReader(compensateSchema(), o.values).text("tables"); }

void emitTables(const CompensateOptions& o, const CompensationTablesResult& r) {
  const auto j = toJson(r);
  std::string others;
  for (const auto& [axis, value] : j["grid"]["pose"].items())
    if (axis != "X" && axis != "Y" && axis != "Z") others += fmt::format("{}{}={:g}", others.empty() ? " with " : ", ", axis, value.get<double>());
  std::string human = fmt::format("Correction tables for {}: {} x {} x {} nodes over the travel of X, Y, Z{}; written to {}/\n", r.setup.machine->name,
                                  r.grid.counts[0], r.grid.counts[1], r.grid.counts[2], others, folderOf(o));
  human += fmt::format("TCP position error left over {} points (nodes and midpoints), um:  largest (rms)\n", r.gridResidual.samples);
  human += fmt::format("  {:<30} {:9.3f} ({:.3f})\n", "uncorrected", r.gridResidual.beforeMax * 1e3, r.gridResidual.beforeRms * 1e3);
  std::string csv = "format,after_max_um,after_rms_um,before_max_um,before_rms_um,moving_forward_max_um,moving_backward_max_um\n";
  for (const auto& t : j["tables"]) {
    const auto& res = t["residual"];
    const std::string format = t["format"];
    const std::string label = format == "grid"          ? "3-D grid, trilinear"
                              : format == "one-axis"    ? fmt::format("{} one-axis functions", r.oneAxis.functions.size())
                              : format == "siemens-cec" ? "Siemens CEC tables"
                              : format == "siemens-lec" ? "Siemens LEC tables per axis"
                              : format == "linuxcnc"    ? "LinuxCNC COMP_FILE per joint"
                              : format == "heidenhain"  ? "HEIDENHAIN .COM tables"
                                                        : "TwinCAT/ISG volumetric model";
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})   carries {}\n", label, res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                         t["carries"].get<std::string>());
    if (res.contains("moving_forward_max_um"))
      human += fmt::format("  {:<30} {:9.3f} / {:.3f} largest moving forward / backward (standing {:.3f})\n", "",
                           res["moving_forward_max_um"].get<double>(), res["moving_backward_max_um"].get<double>(), res["after_max_um"].get<double>());
    if (t.contains("not_carried"))
      for (const auto& left : t["not_carried"]) human += fmt::format("  {:<30} not carried: {}\n", "", left.get<std::string>());
    if (t.contains("along_program"))
      human += fmt::format("  {:<30} {:9.3f} ({:.3f})   along {} (uncorrected {:.3f}; moving as programmed {:.3f})\n", "",
                           t["along_program"]["after_max_um"].get<double>(), t["along_program"]["after_rms_um"].get<double>(), r.checkProgram->file,
                           t["along_program"]["before_max_um"].get<double>(), t["along_program"].value("moving_as_programmed_max_um", 0.0));
    csv += fmt::format("{},{},{},{},{},{},{}\n", t["format"].get<std::string>(), res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                       res["before_max_um"].get<double>(), res["before_rms_um"].get<double>(), res.value("moving_forward_max_um", 0.0),
                       res.value("moving_backward_max_um", 0.0));
  }
  if (!r.isg) human += fmt::format("TwinCAT/ISG volumetric model: none, {}\n", r.isgNotApplicable);
  // The controllers' kinematic data sets, each over the rotary axes' poses and along the check program.
  const auto kinematics = [&](const nlohmann::json& k, const std::string& title, const std::string& format) {
    if (!k["applicable"].get<bool>()) {
      human += fmt::format("{}: none, {}\n", title, k["reason"].get<std::string>());
      return;
    }
    const auto& res = k["residual"];
    human += fmt::format("{} in {}, over {} poses of the rotary axes, um:  largest (rms)\n", title, k["file"].get<std::string>(),
                         res["samples"].get<int>());
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})\n", "nominal parameters", res["before_max_um"].get<double>(), res["before_rms_um"].get<double>());
    human += fmt::format("  {:<30} {:9.3f} ({:.3f})   carries {}\n", "fitted parameters", res["after_max_um"].get<double>(),
                         res["after_rms_um"].get<double>(), k["carries"].get<std::string>());
    for (const auto& left : k["not_carried"]) human += fmt::format("  {:<30} not carried: {}\n", "", left.get<std::string>());
    if (k.contains("along_program"))
      human += fmt::format("  {:<30} {:9.3f} ({:.3f})   along {} (uncorrected {:.3f})\n", "", k["along_program"]["after_max_um"].get<double>(),
                           k["along_program"]["after_rms_um"].get<double>(), r.checkProgram->file, k["along_program"]["before_max_um"].get<double>());
    csv += fmt::format("{},{},{},{},{},{},{}\n", format, res["after_max_um"].get<double>(), res["after_rms_um"].get<double>(),
                       res["before_max_um"].get<double>(), res["before_rms_um"].get<double>(), res.value("moving_forward_max_um", 0.0),
                       res.value("moving_backward_max_um", 0.0));
  };
  const auto& kins = j["linuxcnc_kins"];
  kinematics(kins, kins["applicable"].get<bool>() ? fmt::format("LinuxCNC {} parameters", kins["kins"].get<std::string>()) : "LinuxCNC kinematics parameters",
             "linuxcnc-kins");
  const auto& carr = j["siemens_toolholder"];
  kinematics(carr, carr["applicable"].get<bool>() ? fmt::format("SINUMERIK toolholder $TC_CARR, type {} (and the 5-axis transformation's MD)", carr["type"].get<std::string>())
                                                  : "SINUMERIK toolholder $TC_CARR",
             "siemens-toolholder");
  emit(o, j, human, csv);
}

volatile std::sig_atomic_t stopRequested = 0;
extern "C" void requestStop(int) { stopRequested = 1; }

// Each update's report as the one-off command prints it, and a line on stderr saying when.
void runTablesPeriodically(const CompensateOptions& o) {
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  const OptionReader read(compensateSchema(), o.values);
  const PeriodicTablesRequest request{compensationTablesRequest(loadMachineSetup(o.source), o.values), folderOf(o), *read.number("every"),
                                      read.count("updates").value_or(0)};
  keepTablesCurrent(o.source, request, [] { return stopRequested != 0; },
                    [&](int update, const CompensationTablesResult& r, std::optional<double> moved) {
                      emitTables(o, r);
                      std::cerr << fmt::format("mtacc: update {} at {:%H:%M:%S}: tables for {} written to {}/{}\n", update,
                                               fmt::localtime(std::time(nullptr)), o.source.thermalFile, request.folder,
                                               moved ? fmt::format("; the grid moved by up to {:.3f} um since the last", *moved * 1e3) : "")
                                << std::flush;
                    });
}

}  // namespace

void runCompensationTables(const CompensateOptions& o) {
  if (OptionReader(compensateSchema(), o.values).number("every")) {
    if (o.source.thermalFile.empty()) throw InputError({"", 0, "--every"}, "give --thermal STATE: the temperatures the tables follow");
    return runTablesPeriodically(o);
  }
  const MachineSetup setup = loadMachineSetup(o.source);
  const auto r = compensationTables(setup, compensationTablesRequest(setup, o.values));
  writeCompensationTables(r, folderOf(o));
  emitTables(o, r);
}

}  // namespace mtacc::cli
