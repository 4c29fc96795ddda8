#pragma once
// Workflow `compensate program`: an axis program (G-code) read for a machine, compensated for
// the machine's errors, as G-code text and a summary (corrections, what the tool's path would
// deviate from the program on the machine with its errors, before and after).
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "mtacc/compensation/correction_tables.hpp"
#include "mtacc/compensation/isg_volumetric.hpp"
#include "mtacc/compensation/linuxcnc_kinematics.hpp"
#include "mtacc/compensation/siemens_toolholder.hpp"
#include "mtacc/compensation/program_compensation.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// How far a long compensation has got: lines read, bytes of the file read and its size.
struct StreamProgress {
  long long lines = 0;
  std::uint64_t bytes = 0, size = 0;
  double seconds = 0.0;  // since the start
};

struct ProgramCompensationRequest {
  std::string programFile;
  std::map<int, double> toolLengths;  // G43 H<n>: mm beyond the machine file's tool
  ProgramCompensationOptions options;
  // An errors file of the same machine (e.g. as measured again, or a simulation's truth) the
  // program, as written and compensated, is also run on; "" for none.
  std::string checkErrorsFile;
  // Where the compensated program goes, written as it is produced and put in place at the end
  // (errors name it under `outputKey`); "": kept in the result's `gcode`.
  std::string outputFile, outputKey = "gcode";
  std::function<void(const StreamProgress&)> progress;  // told every 65536 lines, when given
};

struct ProgramCompensationResult {
  MachineSetup setup;
  std::string programFile;
  long long lines = 0, moves = 0;
  CompensationSummary compensated;
  ProgramDeviation deviation;  // the program as written and compensated, on the machine with its errors
  struct Check {
    std::string errorsFile;
    ProgramDeviation deviation;       // the same on that file's errors
    std::vector<std::string> notInModel;  // its non-zero errors that the compensating model holds at zero
  };
  std::optional<Check> check;
  std::string gcode;  // the compensated program, when no output file is given
};

// The program streamed from its file through the compensator to the output, a line at a time:
// memory stays bounded whatever its length. Throws InputError naming the program's file and
// line for bad G-code, and for a compensated point beyond travel; nothing is written then.
ProgramCompensationResult compensateProgramFile(const MachineSetup& setup, const ProgramCompensationRequest& request);
nlohmann::json toJson(const ProgramCompensationResult& result);

// Workflow `compensate --tables`: the correction grid over X, Y, Z at a pose of the other axes,
// its one-axis reduction, the Siemens and LinuxCNC per-axis files and the TwinCAT/ISG (and Etalon)
// volumetric model, each with the residual a controller applying it leaves over the working
// volume; on a 5-axis machine, SINUMERIK's orientable toolholder data set and, for a machine of
// one of LinuxCNC's 5-axis kinematics modules, its parameters, each with the residual it leaves
// over the rotary axes' poses and the errors it cannot carry.
struct CompensationTablesRequest {
  CorrectionGridSpec grid;
  int oneAxisFunctions = 9;  // at most this many one-axis functions (1 to 9)
  int linuxcncType = 1;      // COMP_FILE_TYPE
  int isgRecords = 200;      // records per component error table (TwinCAT/ISG, Etalon): 199 intervals, between the check's lattice points
  std::string checkProgram;  // a test path (G-code) to check each table along, or ""
};

struct CompensationTablesResult {
  MachineSetup setup;
  CorrectionGrid grid;
  OneAxisReduction oneAxis;
  OneAxisReduction ownAxes;  // the functions of each axis's own command (LinuxCNC)
  std::vector<RotaryPositioning> rotary;  // the rotary axes' corrections of their own commands (LEC, LinuxCNC)
  TableResidual gridResidual, oneAxisResidual;  // taken standing
  TableResidual oneAxisMovingResidual;  // the one-axis functions with the reversal trims: SINUMERIK CEC, HEIDENHAIN
  TableResidual ownAxesMovingResidual;  // the own-axis functions with them: SINUMERIK LEC, LinuxCNC
  std::optional<GcodeProgram> checkProgram;
  TableResidual gridAlong, oneAxisAlong, oneAxisMovingAlong, ownAxesMovingAlong;  // along checkProgram
  std::optional<IsgVolumetricModel> isg;
  std::string isgNotApplicable;  // why the machine has no ISG model, when it has none
  TableResidual isgResidual, isgAlong;
  std::optional<LinuxcncKinematicsFit> kins;
  std::string kinsNotApplicable;  // why the machine has no LinuxCNC kinematics parameters, when it has none
  TableResidual kinsAlong;        // along checkProgram
  std::optional<SiemensToolholderFit> toolholder;
  std::string toolholderNotApplicable;  // why the machine has no SINUMERIK toolholder data set, when it has none
  TableResidual toolholderAlong;        // along checkProgram
  std::vector<std::pair<std::string, std::string>> files;  // name, content
};

// Throws InputError for a machine without linear X, Y, Z, or more than 256 nodes on an axis for
// LinuxCNC.
CompensationTablesResult compensationTables(const MachineSetup& setup, const CompensationTablesRequest& request);
nlohmann::json toJson(const CompensationTablesResult& result);
// Every file of `result` in `folder` (created if missing), each written whole or not at all.
// Throws InputError (key "tables") for a folder or a file that cannot be written.
void writeCompensationTables(const CompensationTablesResult& result, const std::string& folder);

// The tables kept up with a thermal state that a temperature logger rewrites, as seed 003's
// controller read its compensation every 60 s (§2.7): each period the machine is set up again
// from `source` (its thermal state read anew), the tables computed and written to `folder`,
// and `updated` told (the update's number from 1, the tables, and how far the grid's
// corrections moved since the last, mm; none the first time). Stops after `updates` writes
// (0: no limit) or when `stop` returns true, asked every 20 ms while waiting. A state that
// cannot be read throws its InputError, the last tables left in place.
struct PeriodicTablesRequest {
  CompensationTablesRequest tables;
  std::string folder;
  double periodSeconds = 60.0;
  int updates = 0;
};
using TablesUpdated = std::function<void(int update, const CompensationTablesResult& result, std::optional<double> moved)>;
void keepTablesCurrent(const MachineSource& source, const PeriodicTablesRequest& request, const std::function<bool()>& stop,
                       const TablesUpdated& updated);

}  // namespace mtacc
