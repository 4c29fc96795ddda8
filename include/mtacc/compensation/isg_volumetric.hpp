#pragma once
// Beckhoff TwinCAT CNC / ISG kernel volumetric compensation (TF5280): the controller holds the
// ISO 230-1 model itself and corrects the tool position (not its direction) from it. mtacc writes
// the model as its parameter files: the position errors (ISO names, mm and rad) and each axis's
// component errors as look-up tables over its travel (arguments in mm and degrees, linear between
// the records: interpolation GRID), in ISG CSV and in Etalon's exchange format ("Vendor" variant),
// with the compensation list naming the axes, the chain and the files.
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct IsgVolumetricModel {
  // ISG `chain`: the commanded axes from the workpiece to the tool (the workpiece side from the
  // workpiece to the bed, then the tool side from the bed); the first `workpieceAxes` carry the workpiece.
  std::string chain;
  int workpieceAxes = 0;
  std::vector<std::pair<std::string, double>> positionErrors;  // ISO name, mm or rad
  struct ComponentTable {
    int axis = 0;                           // index into Machine::axes
    std::vector<double> arguments;          // mm or degrees
    std::array<std::vector<double>, 6> values;  // EX. EY. EZ. (mm) EA. EB. EC. (rad) at the arguments
  };
  std::vector<ComponentTable> components;
  // The spindle's offsets from the last commanded axis (its location errors X0, Y0, Z0, mm): they
  // turn with the tool, so the controller takes them as the tool's kinematic offsets (P-TOOL-00009),
  // not in the files; stated in them, and applied by the controller's model below.
  Vec3 toolOffset = Vec3::Zero();
  std::vector<std::string> notCarried;  // what the machine's model holds that the files and the tool data cannot
};

// Throws InputError for a machine ISG's model does not describe: commanded axes other than linear
// X, Y, Z and rotary A, B, C along the machine's X, Y, Z; `records` (2 to 10000) per table, spread
// over the axis's travel (a continuous rotary axis: 0 to 360 degrees).
IsgVolumetricModel isgVolumetricModel(const Machine& machine, const ErrorModel& errors, int records = 200);

// The model the controller evaluates from the files and the tool's offsets: the position errors,
// the tables linear between the records, the end values beyond, and the spindle's offsets.
ErrorModel isgControllerModel(const Machine& machine, const IsgVolumetricModel& model);

// The controller's correction of the X, Y, Z commands at the commands q: the position its model
// predicts, put back where the nominal machine has it (the tool direction is not corrected).
// Stateful (it keeps the last Jacobian): one per thread.
CommandCorrection isgCorrection(const std::shared_ptr<const Machine>& machine, const ErrorModel& controllerModel);

// The files: ISG CSV (`//` comments, the position errors' header and row, then per axis a file
// break `#`, its header "<axis> EX<axis> ... EC<axis>" and a row per record), Etalon exchange
// ("[NAME]" blocks with "VALUE = " or "Gridpoints = { argument value ... }"), and the compensation
// list (axis numbers, chain, workpiece_axes, file[0], file_format[0], interpolation).
std::string isgCsv(const Machine& machine, const IsgVolumetricModel& model);
std::string etalonExchange(const Machine& machine, const IsgVolumetricModel& model);
std::string isgCompensationList(const Machine& machine, const IsgVolumetricModel& model, const std::string& csvFile);

}  // namespace mtacc
