#include "mtacc/workflows/compensation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <filesystem>
#include <iterator>
#include <set>
#include <thread>

#include "mtacc/core/input_error.hpp"
#include "mtacc/compensation/heidenhain_tables.hpp"
#include "mtacc/compensation/isg_leadscrew.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/core/text_file.hpp"

namespace mtacc {

ProgramCompensationResult compensateProgramFile(const MachineSetup& setup, const ProgramCompensationRequest& request) {
  const auto& o = request.options;
  if (!(o.tolerance > 0 && o.tolerance <= 1.0))
    throw InputError({"", 0, "tolerance"}, fmt::format("the tolerance must lie in (0, 1000] um, not {} um", o.tolerance * 1e3));
  if (!(o.directionTolerance > 0 && o.directionTolerance <= 0.01))
    throw InputError({"", 0, "direction_tolerance"},
                     fmt::format("the direction tolerance must lie in (0, 10000] urad, not {} urad", o.directionTolerance * 1e6));
  ProgramCompensationResult r;
  r.setup = setup;
  r.programFile = request.programFile;
  const auto& m = setup.machine;
  std::optional<ErrorModel> other;
  if (!request.checkErrorsFile.empty()) other = loadErrors(*m, request.checkErrorsFile);
  TextLines text(request.programFile);
  GcodeLineReader reader(request.programFile, *m, {{}, request.toolLengths});
  ProgramCompensator compensator(m, setup.errors, request.options);
  DeviationSum deviation(m, setup.errors);
  std::optional<DeviationSum> checked;
  if (other) checked.emplace(m, *other);
  std::optional<AtomicFile> body;  // the program after its preamble, which holds the figures known at the end
  if (!request.outputFile.empty()) body.emplace(request.outputFile, request.outputKey);
  CompensatedGcodeWriter writer(*m);
  std::string written;  // to `body` a block at a time
  GcodeLine line;
  std::optional<GcodeLine> percent;
  const auto started = std::chrono::steady_clock::now();
  std::string_view raw;
  while (text.next(raw)) {
    const GcodeMove* move = reader.read(raw, line);
    if (reader.lines() == 1 && isPercentLine(line)) {
      percent = line;
      continue;
    }
    std::span<const CompensatedPoint> points;
    if (move) {
      points = compensator.compensate(*move, line.move);
      if (const auto& c = compensator.summary(); !c.travelViolation.empty())
        throw InputError({request.programFile, c.travelViolationLine, "travel"}, "the compensated commands leave the travel: " + c.travelViolation);
      deviation.add(points, *move);
      if (checked) checked->add(points, *move);
      points = points.subspan(1);
    }
    writer.line(written, line, move, points);
    if (body && written.size() >= (size_t{1} << 20)) {
      body->write(written);
      written.clear();
    }
    if (request.progress && reader.lines() % 65536 == 0)
      request.progress({reader.lines(), text.bytesRead(), text.size(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()});
  }
  r.lines = reader.lines();
  r.moves = reader.moves();
  if (r.moves == 0) throw InputError({request.programFile, reader.lines(), "program"}, "the program ends without moving an axis: nothing to compensate");
  r.compensated = compensator.summary();
  r.deviation = deviation.result();
  if (other) {
    r.check = ProgramCompensationResult::Check{request.checkErrorsFile, checked->result(), {}};
    std::set<std::string> modelled;
    for (const auto& p : nonZeroParameters(*m, setup.errors)) modelled.insert(p.name);
    for (const auto& p : nonZeroParameters(*m, *other))
      if (!modelled.contains(p.name)) r.check->notInModel.push_back(p.name);
  }
  const auto& d = r.deviation;
  const std::string header = fmt::format(
      "mtacc: {} compensated for {} and its errors ({} non-zero parameters)\n"
      "tolerance {:g} um, {:g} urad; TCP deviation on the machine with errors: before {:.2f} um, after {:.3f} um (largest)",
      request.programFile, m->name, nonZeroParameters(*m, setup.errors).size(), request.options.tolerance * 1e3,
      request.options.directionTolerance * 1e6, d.before.maxPosition * 1e3, d.after.maxPosition * 1e3);
  const std::string preamble = compensatedGcodePreamble(percent ? &*percent : nullptr, header);
  if (!body) {
    r.gcode = preamble + written;
    return r;
  }
  body->write(written);
  AtomicFile output(request.outputFile, request.outputKey);
  output.write(preamble);
  output.append(*body);
  output.commit();
  return r;
}

nlohmann::json toJson(const ProgramCompensationResult& r) {
  const auto& c = r.compensated;
  const Machine& m = *r.setup.machine;
  auto deviation = [](const PathDeviation& d) {
    return nlohmann::json{{"max_position_um", d.maxPosition * 1e3}, {"rms_position_um", d.rmsPosition * 1e3},
                          {"max_direction_urad", d.maxDirection * 1e6}, {"samples", d.samples}};
  };
  nlohmann::json correction = nlohmann::json::object();
  for (int k = 0; k < m.commandedCount(); ++k) {
    const Axis& a = m.axes[static_cast<size_t>(k)];
    correction[a.name] = toDisplay(c.largestCorrection[static_cast<size_t>(k)], a.isRotary() ? Dimension::Angle : Dimension::Length);
  }
  return {{"machine", m.name},
          {"program", r.programFile},
          {"lines", r.lines},
          {"moves", r.moves},
          {"written_points", c.written},
          {"largest_correction_um_urad", correction},
          {"largest_residual_um", c.largestResidual * 1e3},
          {"not_converged", c.notConverged},
          {"singular", c.singular},
          {"first_problem_line", c.firstProblemLine},
          {"deviation_before", deviation(r.deviation.before)},
          {"deviation_after", deviation(r.deviation.after)},
          {"check", r.check ? nlohmann::json{{"errors", r.check->errorsFile}, {"deviation_before", deviation(r.check->deviation.before)},
                                             {"deviation_after", deviation(r.check->deviation.after)}, {"not_in_model", r.check->notInModel}}
                            : nlohmann::json(nullptr)}};
}

namespace {

// The one-axis functions as CSV: which axis's command each corrects, as a function of which.
std::string oneAxisCsv(const Machine& m, const OneAxisReduction& r, const CorrectionGrid& g) {
  const char* names[3] = {"X", "Y", "Z"};
  std::string out = fmt::format(
      "# mtacc one-axis correction functions for {} (seed 003 §11): add each function of the input axis's command to the output "
      "axis's command; linear between the positions, the end value beyond\n"
      "# {} functions; they leave {:.3f} um (largest) of the grid's corrections; pose of the other axes: {}\n"
      "input_axis,output_axis,position_mm,correction_mm\n",
      m.name, r.functions.size(), r.residualMax * 1e3, m.describePose(g.pose));
  auto it = std::back_inserter(out);
  for (const auto& f : r.functions)
    for (size_t n = 0; n < f.positions.size(); ++n)
      fmt::format_to(it, "{},{},{:.6f},{:.7f}\n", names[f.input], names[f.output], f.positions[n], f.values[n]);
  return out;
}

nlohmann::json residualJson(const TableResidual& r) {
  nlohmann::json j = {{"before_max_um", r.beforeMax * 1e3}, {"before_rms_um", r.beforeRms * 1e3}, {"after_max_um", r.afterMax * 1e3},
                      {"after_rms_um", r.afterRms * 1e3}, {"samples", r.samples}};
  if (r.forwardMax > 0.0 || r.backwardMax > 0.0) {
    j["moving_forward_max_um"] = r.forwardMax * 1e3;
    j["moving_backward_max_um"] = r.backwardMax * 1e3;
  }
  if (r.programmedMax > 0.0) j["moving_as_programmed_max_um"] = r.programmedMax * 1e3;
  return j;
}

nlohmann::json kinsJson(const LinuxcncKinematicsFit& fit) {
  const auto pins = [](const LinuxcncKinematics& k) {
    nlohmann::json j;
    for (const auto& [pin, value] : k.pins()) j[pin] = value;
    return j;
  };
  const auto um = [](const Vec3& mm) { return nlohmann::json{mm.x() * 1e3, mm.y() * 1e3, mm.z() * 1e3}; };
  return {{"applicable", true}, {"kins", fit.actual.name()}, {"file", "linuxcnc-kins.hal"},
          {"pins_mm", pins(fit.actual)}, {"nominal_pins_mm", pins(fit.nominal)},
          {"sign", {{"tilt", fit.sign[0]}, {"c", fit.sign[1]}}},
          {"world_origin_mm", {fit.worldOrigin.x(), fit.worldOrigin.y(), fit.worldOrigin.z()}},
          {"work_offset_um", um(fit.workOffset)},
          {"joint_origin_mm", {fit.jointOrigin.x(), fit.jointOrigin.y(), fit.jointOrigin.z()}},
          {"joint_origin_shift_um", um(fit.jointOriginShift)},
          {"carries", fit.actual.carries()}, {"not_carried", fit.notCarried},
          {"residual", residualJson(fit.residual)}};
}

nlohmann::json toolholderJson(const SiemensToolholderFit& fit) {
  const auto xyz = [](const Vec3& v, double unit) { return nlohmann::json{v.x() * unit, v.y() * unit, v.z() * unit}; };
  const auto dataSet = [&](const SiemensToolholder& h) {
    nlohmann::json l = nlohmann::json::array(), v = nlohmann::json::array();
    for (const Vec3& vector : h.l) l.push_back(xyz(vector, 1.0));
    for (const Vec3& vector : h.v) v.push_back(xyz(vector, 1.0));
    return nlohmann::json{{"l_mm", l}, {"v", v}, {"offset_deg", {h.offset[0] / kDeg, h.offset[1] / kDeg}}};
  };
  return {{"applicable", true}, {"type", std::string(1, fit.actual.type)}, {"file", "siemens-toolholder.spf, siemens-trafo5.ini"},
          {"axes", fit.actual.axes}, {"data_set", dataSet(fit.actual)}, {"nominal_data_set", dataSet(fit.nominal)},
          {"world_origin_mm", xyz(fit.worldOrigin, 1.0)}, {"work_offset_um", xyz(fit.workOffset, 1e3)},
          {"work_rotation_urad", xyz(fit.workRotation, 1e6)}, {"carries", fit.actual.carries()}, {"not_carried", fit.notCarried},
          {"residual", residualJson(fit.residual)}};
}

}  // namespace

CompensationTablesResult compensationTables(const MachineSetup& setup, const CompensationTablesRequest& request) {
  if (request.oneAxisFunctions < 1 || request.oneAxisFunctions > 9)
    throw InputError({"", 0, "functions"}, fmt::format("{} one-axis functions: give 1 to 9", request.oneAxisFunctions));
  if (request.linuxcncType != 0 && request.linuxcncType != 1)
    throw InputError({"", 0, "linuxcnc_type"}, "COMP_FILE_TYPE is 0 (positions) or 1 (trims)");
  CompensationTablesResult r;
  r.setup = setup;
  if (!request.checkProgram.empty()) r.checkProgram = readGcodeProgram(request.checkProgram, *setup.machine);
  r.grid = correctionGrid(setup.machine, setup.errors, request.grid);
  r.oneAxis = reduceToOneAxisFunctions(r.grid, request.oneAxisFunctions);
  r.ownAxes = reduceToOneAxisFunctions(r.grid, 9);
  std::erase_if(r.ownAxes.functions, [](const AxisFunction& f) { return f.input != f.output; });
  const auto& m = setup.machine;
  r.rotary = rotaryPositioning(m, setup.errors, r.grid.pose);
  std::array<ReversalTrims, 3> trims;
  for (const auto& f : r.ownAxes.functions) trims[static_cast<size_t>(f.input)] = reversalTrims(m, setup.errors, r.grid, f.input);
  for (size_t a = 0; a < 3; ++a)
    if (trims[a].forward.empty()) trims[a] = {std::vector<double>(static_cast<size_t>(r.grid.counts[a]), 0.0), std::vector<double>(static_cast<size_t>(r.grid.counts[a]), 0.0)};
  const auto grid = [&](const Vec3& p) { return r.grid.interpolate(p); };
  const auto oneAxis = [&](const Vec3& p) { return r.oneAxis.correction(p); };
  const DirectedCorrection ownAxes = directedCorrection(r.grid, r.ownAxes, trims), oneAxisMoving = directedCorrection(r.grid, r.oneAxis, trims);
  r.gridResidual = tableResidual(m, setup.errors, r.grid, grid);
  r.oneAxisResidual = tableResidual(m, setup.errors, r.grid, oneAxis);
  r.oneAxisMovingResidual = tableResidual(m, setup.errors, r.grid, oneAxisMoving);
  r.ownAxesMovingResidual = tableResidual(m, setup.errors, r.grid, ownAxes, 41, r.rotary);
  if (r.checkProgram) {
    r.gridAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, grid);
    r.oneAxisAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, oneAxis);
    r.oneAxisMovingAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, oneAxisMoving);
    r.ownAxesMovingAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, ownAxes, r.rotary);
  }
  try {
    r.isg = isgVolumetricModel(*m, setup.errors, request.isgRecords);
  } catch (const InputError& notIsg) {
    r.isgNotApplicable = notIsg.reason();
  }
  r.files.emplace_back("grid.csv", correctionGridCsv(*m, r.grid));
  r.files.emplace_back("one-axis.csv", oneAxisCsv(*m, r.oneAxis, r.grid));
  const std::string pose = m->describePose(r.grid.pose);
  const std::vector<AxisReversalTable> reversal = axisReversalTables(*m, r.grid, trims, r.rotary);
  r.files.emplace_back("siemens-cec.ini", siemensCecTables(r.oneAxis.functions, reversal, pose));
  r.files.emplace_back("siemens-lec.ini", siemensLecTables(r.ownAxes.functions, *m, r.rotary, pose));
  if (!reversal.empty()) r.files.emplace_back("siemens-cec-reversal.ini", siemensCecTables({}, reversal, pose));
  const char* names[3] = {"X", "Y", "Z"};
  for (const auto& f : r.ownAxes.functions)
    r.files.emplace_back(fmt::format("linuxcnc-{}.comp", names[f.input]), linuxcncCompFile(f, trims[static_cast<size_t>(f.input)], request.linuxcncType));
  for (const auto& rotary : r.rotary)
    r.files.emplace_back(fmt::format("linuxcnc-{}.comp", m->axes[static_cast<size_t>(rotary.axis)].name), linuxcncCompFile(rotary, request.linuxcncType));
  for (auto& file : heidenhainTables(r.oneAxis, trims)) r.files.push_back(std::move(file));
  if (r.isg) {
    // The reversal in bilateral LSEC lists beside the volumetric model; they hold whole 0.1 um,
    // and the residual is that of the trims as written.
    const auto isgTrims = roundedTrims(trims, kIsgLeadscrewUnit);
    const DirectedCorrection controller = directedCorrection(r.grid, isgCorrection(m, isgControllerModel(*m, *r.isg)), isgTrims);
    r.isgResidual = tableResidual(m, setup.errors, r.grid, controller);
    if (r.checkProgram) r.isgAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, controller);
    r.files.emplace_back("isg-volcomp.csv", isgCsv(*m, *r.isg));
    r.files.emplace_back("isg-volcomp.lis", isgCompensationList(*m, *r.isg, "isg-volcomp.csv"));
    for (const AxisReversalTable& t : axisReversalTables(*m, r.grid, isgTrims, r.rotary))
      r.files.emplace_back(fmt::format("isg-lsec-{}.lis", t.axis), isgLeadscrewList(*m, t));
    r.files.emplace_back("etalon-exchange.txt", etalonExchange(*m, *r.isg));
  }
  try {
    r.kins = fitLinuxcncKinematics(m, setup.errors);
    r.files.emplace_back("linuxcnc-kins.hal", linuxcncKinematicsHal(*m, *r.kins));
    if (r.checkProgram) r.kinsAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, linuxcncCorrection(m, *r.kins));
  } catch (const InputError& notKins) {
    r.kinsNotApplicable = notKins.reason();
  }
  try {
    r.toolholder = fitSiemensToolholder(m, setup.errors);
    r.files.emplace_back("siemens-toolholder.spf", siemensToolholderProgram(*m, *r.toolholder));
    r.files.emplace_back("siemens-trafo5.ini", siemensTrafo5MachineData(*m, *r.toolholder));
    if (r.checkProgram)
      r.toolholderAlong = tableResidualAlong(m, setup.errors, *r.checkProgram, r.grid, siemensToolholderCorrection(m, *r.toolholder));
  } catch (const InputError& notToolholder) {
    r.toolholderNotApplicable = notToolholder.reason();
  }
  return r;
}

nlohmann::json toJson(const CompensationTablesResult& r) {
  const char* names[3] = {"X", "Y", "Z"};
  nlohmann::json functions = nlohmann::json::array();
  for (const auto& f : r.oneAxis.functions) functions.push_back({{"input", names[f.input]}, {"output", names[f.output]}, {"rms_um", f.rms * 1e3}});
  nlohmann::json files = nlohmann::json::array();
  std::string heidenhainFiles, linuxcncFiles, isgFiles, lecFiles;
  for (const auto& file : r.files) {
    const std::string& name = file.first;
    files.push_back(name);
    const auto add = [&](std::string& list) { list += (list.empty() ? "" : ", ") + name; };
    if (name.starts_with("heidenhain")) add(heidenhainFiles);
    if (name.ends_with(".comp")) add(linuxcncFiles);
    if (name == "siemens-lec.ini" || name == "siemens-cec-reversal.ini") add(lecFiles);
    if (name.starts_with("isg-") || name.starts_with("etalon-")) add(isgFiles);
  }
  const Machine& m = *r.setup.machine;
  // What of the reversal each table carries: none (taken standing), each axis's along its own
  // motion (a table of its own command moving each way), or the linear axes' only.
  enum class Reversal { None, Own, OwnLinear };
  const auto ownOf = [&](bool linearOnly) {
    return [&m, linearOnly](int axis, int component) {
      const Axis& a = m.axes[static_cast<size_t>(axis)];
      return !(axis < m.commandedCount() && a.ownComponent() == component && (!linearOnly || !a.isRotary()));
    };
  };
  const auto row = [&](nlohmann::json t, const TableResidual& residual, const TableResidual& along, Reversal reversal,
                       std::vector<std::string> notCarried = {}) {
    const auto left = reversal == Reversal::None ? reversalFunctions(m, r.setup.errors)
                                                 : reversalFunctions(m, r.setup.errors, ownOf(reversal == Reversal::OwnLinear));
    if (!left.empty())
      notCarried.push_back(fmt::format("the reversal terms of {} ({})", fmt::join(left, ", "),
                                       reversal == Reversal::None ? "the table is taken standing"
                                       : reversal == Reversal::Own ? "the tables take each axis's reversal along its own motion only"
                                                                   : "the tables take the linear axes' reversal along their own motion only"));
    if (!notCarried.empty()) t["not_carried"] = notCarried;
    t["residual"] = residualJson(residual);
    if (r.checkProgram) t["along_program"] = residualJson(along);
    return t;
  };
  const auto& g = r.grid;
  nlohmann::json tables = {
      row({{"format", "grid"}, {"file", "grid.csv"}, {"carries", "the position error everywhere, trilinear between the nodes"}}, r.gridResidual,
          r.gridAlong, Reversal::None),
      row({{"format", "one-axis"}, {"file", "one-axis.csv"}, {"functions", functions}, {"reduction_residual_max_um", r.oneAxis.residualMax * 1e3},
           {"carries", "the sum of one-axis functions; not the interactions (an angular error times another axis's travel)"}},
          r.oneAxisResidual, r.oneAxisAlong, Reversal::None),
      row({{"format", "siemens-cec"}, {"file", "siemens-cec.ini"},
           {"carries", "the one-axis functions above, one CEC table each (input and output axis by the machine file's names); moving, "
                       "each axis's reversal in two tables on its own command, one per direction ($AN_CEC_DIRECTION 1 and -1)"}},
          r.oneAxisMovingResidual, r.oneAxisMovingAlong, Reversal::Own),
      row({{"format", "siemens-lec"}, {"files", lecFiles},
           {"carries", "each axis's correction of its own command (as LinuxCNC's), the rotary axes' by their own angular positioning; moving, "
                       "each axis's reversal in siemens-cec-reversal.ini's tables by direction (in place of siemens-cec.ini); not the "
                       "cross-axis terms"}},
          r.ownAxesMovingResidual, r.ownAxesMovingAlong, Reversal::Own),
      row({{"format", "linuxcnc"}, {"files", linuxcncFiles},
           {"carries", "each axis's correction of its own command, moving forward and backward (its reversal), the rotary axes' by their own "
                       "angular positioning; not the cross-axis terms (squareness, straightness)"}},
          r.ownAxesMovingResidual, r.ownAxesMovingAlong, Reversal::Own),
      row({{"format", "heidenhain"}, {"files", heidenhainFiles},
           {"carries", "the one-axis functions above, one compensation-value table per input axis with a column per output axis; "
                       "moving, each linear axis's reversal in its BACKLASH column"}},
          r.oneAxisMovingResidual, r.oneAxisMovingAlong, Reversal::OwnLinear)};
  if (r.isg) {
    std::vector<std::string> notCarried;
    std::copy_if(r.isg->notCarried.begin(), r.isg->notCarried.end(), std::back_inserter(notCarried),
                 [](const std::string& left) { return !left.starts_with("the reversal terms"); });
    tables.push_back(row({{"format", "isg-volumetric"}, {"files", isgFiles}, {"chain", r.isg->chain}, {"workpiece_axes", r.isg->workpieceAxes},
                          {"carries", "the ISO 230-1 model, evaluated by the controller at every pose: the position errors and each "
                                      "axis's component errors, linear between the records; the spindle's offsets as the tool's; moving, "
                                      "each axis's reversal in bilateral leadscrew lists isg-lsec-*.lis to 0.1 um (Etalon's exchange has "
                                      "no direction)"},
                          {"tool_offset_mm", {r.isg->toolOffset.x(), r.isg->toolOffset.y(), r.isg->toolOffset.z()}}},
                         r.isgResidual, r.isgAlong, Reversal::Own, notCarried));
  }
  nlohmann::json j = {{"machine", m.name},
                      {"grid", {{"nodes", g.counts}, {"start_mm", g.start}, {"step_mm", g.step}, {"pose", poseJson(m, g.pose.data())}}},
                      {"tables", tables},
                      {"files", files}};
  nlohmann::json rotary = nlohmann::json::array();
  for (const auto& t : r.rotary) {
    double correction = 0.0, reversal = 0.0;
    for (size_t n = 0; n < t.positions.size(); ++n) {
      correction = std::max(correction, std::abs(t.standing[n]));
      reversal = std::max(reversal, std::abs(t.forward[n] - t.reverse[n]));
    }
    rotary.push_back({{"axis", m.axes[static_cast<size_t>(t.axis)].name}, {"positions", t.positions.size()},
                      {"step_deg", (t.positions[1] - t.positions[0]) / kDeg}, {"modulo", t.modulo},
                      {"largest_correction_urad", correction * 1e6}, {"largest_reversal_urad", reversal * 1e6}});
  }
  j["rotary_positioning"] = rotary;
  j["isg_volumetric"] = r.isg ? nlohmann::json{{"applicable", true}} : nlohmann::json{{"applicable", false}, {"reason", r.isgNotApplicable}};
  j["linuxcnc_kins"] = r.kins ? kinsJson(*r.kins) : nlohmann::json{{"applicable", false}, {"reason", r.kinsNotApplicable}};
  if (r.kins && r.checkProgram) j["linuxcnc_kins"]["along_program"] = residualJson(r.kinsAlong);
  j["siemens_toolholder"] = r.toolholder ? toolholderJson(*r.toolholder)
                                         : nlohmann::json{{"applicable", false}, {"reason", r.toolholderNotApplicable}};
  if (r.toolholder && r.checkProgram) j["siemens_toolholder"]["along_program"] = residualJson(r.toolholderAlong);
  if (r.checkProgram) j["check_program"] = r.checkProgram->file;
  return j;
}

void writeCompensationTables(const CompensationTablesResult& result, const std::string& folder) {
  const std::string key = "tables";
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw InputError({"", 0, key}, fmt::format("{}: cannot create the folder: {}", folder, error.message()));
  for (const auto& [name, content] : result.files) writeFileAtomically((std::filesystem::path(folder) / name).string(), content, key);
}

void keepTablesCurrent(const MachineSource& source, const PeriodicTablesRequest& request, const std::function<bool()>& stop,
                       const TablesUpdated& updated) {
  if (source.thermalFile.empty()) throw InputError({"", 0, "every"}, "give a thermal state: the temperatures the tables follow");
  if (!(request.periodSeconds > 0 && request.periodSeconds <= 86400)) throw InputError({"", 0, "every"}, "a period above 0 and at most a day, in s");
  if (request.updates < 0) throw InputError({"", 0, "updates"}, "0 (until stopped) or more updates");
  std::optional<CorrectionGrid> previous;
  for (int update = 1; !stop(); ++update) {
    const auto result = compensationTables(loadMachineSetup(source), request.tables);
    writeCompensationTables(result, request.folder);
    std::optional<double> moved;
    if (previous) {
      moved = 0.0;
      for (size_t n = 0; n < result.grid.corrections.size(); ++n)
        moved = std::max(*moved, (result.grid.corrections[n] - previous->corrections[n]).norm());
    }
    updated(update, result, moved);
    previous = result.grid;
    if (request.updates > 0 && update >= request.updates) break;
    const auto next = std::chrono::steady_clock::now() + std::chrono::duration<double>(request.periodSeconds);
    while (!stop() && std::chrono::steady_clock::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace mtacc
