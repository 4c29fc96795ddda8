#pragma once
// Controller-side compensation (issue 17, item 3): the corrections of the linear axes' commands
// that put the TCP where the nominal machine puts it, tabulated as a controller holds them, and
// what a controller applying each table leaves of the error.
//   * a 3-D grid of correction vectors over X, Y, Z, interpolated trilinearly (the generic form;
//     Fanuc's 3-D error compensation);
//   * its reduction to additive one-axis functions (seed 003 §11): the correction of one axis as
//     a function of one axis's command, chosen by least squares, with the residual they leave;
//     LinuxCNC's COMP_FILE and Siemens LEC carry the functions of an axis's own command, Siemens
//     CEC any of them.
// The tables correct the position only (the rotary axes stay at the pose the grid is taken at).
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mtacc/compensation/nc_program.hpp"
#include "mtacc/compensation/rotary_positioning.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/inverse_with_errors.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// The linear axes the tables correct, by index 0, 1, 2.
inline constexpr const char* kLinearAxisNames[3] = {"X", "Y", "Z"};

// The inverse error model as a controller's table of linear-axis corrections uses it: the
// position only (the rotary axes stay), to 0.1 nm.
ErrorIkOptions positionCorrectionOptions();

struct CorrectionGridSpec {
  std::array<int, 3> counts{21, 21, 21};  // nodes along X, Y, Z, spread over each axis's travel
  std::vector<double> pose;               // the other commanded axes (mm, rad); empty: all zero
  int threads = kAllCores;                // Z layers in parallel; the result is the same for any count
};

struct CorrectionGrid {
  std::array<int, 3> axes{};            // indices of X, Y, Z among the commanded axes
  std::array<double, 3> start{}, step{};  // mm
  std::array<int, 3> counts{};
  std::vector<double> pose;             // every commanded axis; the grid's own axes are overwritten per node
  std::vector<Vec3> corrections;        // mm, node (i, j, k) at i + counts[0] * (j + counts[1] * k)

  double node(int axis, int index) const { return start[static_cast<size_t>(axis)] + index * step[static_cast<size_t>(axis)]; }
  const Vec3& at(int i, int j, int k) const {
    return corrections[static_cast<size_t>(i + counts[0] * (j + counts[1] * k))];
  }
  // Trilinear between the nodes, the end value beyond them.
  Vec3 interpolate(const Vec3& xyz) const;
};

// The inverse error model's correction at every node (position only, by the linear axes), nodes
// in order with the Jacobian kept and each node started from its neighbours' corrections (the
// previous row's change along X added to the node before). Throws InputError when
// the machine has no linear X, Y, Z or an axis has no travel to spread the nodes over.
CorrectionGrid correctionGrid(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGridSpec& spec);

// A correction added to the command of `output` as a function of the command of `input`
// (both among X, Y, Z: 0, 1, 2), on the grid's nodes of `input`, linear between them.
struct AxisFunction {
  int input = 0, output = 0;
  std::vector<double> positions;  // mm
  std::vector<double> values;     // mm
  double rms = 0.0;               // mm, over the nodes
  double at(double position) const;
};

struct OneAxisReduction {
  std::vector<AxisFunction> functions;  // the largest first
  double residualMax = 0.0, residualRms = 0.0;  // mm: |grid correction - sum of the functions| over the nodes
  Vec3 correction(const Vec3& xyz) const;
};

// The least-squares decomposition of the grid's corrections into additive one-axis functions:
// on a full grid, the main effects (the mean over the other two axes, less the grand mean, which
// goes to the output axis's own function); the `maxFunctions` largest by their RMS are kept.
OneAxisReduction reduceToOneAxisFunctions(const CorrectionGrid& grid, int maxFunctions = 9);

// How far the TCP is from where the nominal machine puts it, with the commands as written
// (before) and corrected by `correction` as the controller applies it (after), over a lattice
// of the grid's nodes and the midpoints between them (at most `perAxis` per axis).
// Over the lattice the machine stands at each point; moving, X, Y and Z move forward (or backward)
// through it, so the reversal errors and the controller's direction-dependent corrections act
// (a coarser lattice, at most 11 per axis): what the table leaves on a real move.
struct TableResidual {
  double beforeMax = 0.0, beforeRms = 0.0, afterMax = 0.0, afterRms = 0.0;  // mm
  int samples = 0;
  double forwardMax = 0.0, backwardMax = 0.0;  // mm, after, moving forward and backward
  double programmedMax = 0.0;                   // mm, after, along a program: each axis moving as the program moves it
};
// `rotary`: the rotary axes' own corrections the controller applies beside (standing).
TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid,
                            const std::function<Vec3(const Vec3&)>& correction, int perAxis = 41,
                            const std::vector<RotaryPositioning>& rotary = {});
// A correction that depends on every command (a controller holding the error model itself).
using CommandCorrection = std::function<Vec3(const std::vector<double>& q)>;
TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid,
                            const CommandCorrection& correction, int perAxis = 41, const std::vector<RotaryPositioning>& rotary = {});
// A correction that depends on the directions the axes move in (+1, -1, 0 per commanded axis;
// empty standing): LinuxCNC's forward and reverse trims.
using DirectedCorrection = std::function<Vec3(const std::vector<double>& q, const std::vector<int>& direction)>;
TableResidual tableResidual(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid,
                            const DirectedCorrection& correction, int perAxis = 41, const std::vector<RotaryPositioning>& rotary = {});

// The same along a program's feed moves (each sampled at 17 points, ends included), standing and
// (programmedMax) each axis moving as the program moves it, its reversals acting; the controller
// correcting the X, Y, Z commands continuously as it interpolates them; the program's other axes
// as programmed, the machine file's tool (G43 lengths are not applied: the tables are made for
// that tool). A test path shows what each table does where the machine works.
TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& grid, const std::function<Vec3(const Vec3&)>& correction,
                                 const std::vector<RotaryPositioning>& rotary = {});
TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& grid, const CommandCorrection& correction,
                                 const std::vector<RotaryPositioning>& rotary = {});
TableResidual tableResidualAlong(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const GcodeProgram& program,
                                 const CorrectionGrid& grid, const DirectedCorrection& correction,
                                 const std::vector<RotaryPositioning>& rotary = {});

// The motion functions with a reversal term of non-zero width, by name ("EXX"): what a
// controller's model of the machine standing still does not carry. `among(axis, component)`
// chooses (all when empty): a table moving each way on an axis's own command carries the
// reversal of its own positioning (EXX, ECC) and not the others.
std::vector<std::string> reversalFunctions(const Machine& machine, const ErrorModel& errors,
                                           const std::function<bool(int axis, int component)>& among = {});
// The file forms, each stating its units, grid and what it cannot carry in its header.
// Generic grid: CSV "x_mm,y_mm,z_mm,dx_mm,dy_mm,dz_mm", '#' comment lines first.
std::string correctionGridCsv(const Machine& machine, const CorrectionGrid& grid);
// What the reversal errors add to an axis's own correction with it moving forward and backward
// (mm, at its grid nodes; the other two linear axes at their middle nodes, standing): the
// corrections solved with the axis moving each way less the one solved standing.
struct ReversalTrims {
  std::vector<double> forward, reverse;
};
// True when a correction column (a trim, a table's values) holds anything to apply.
bool anyNonZero(const std::vector<double>& values);
ReversalTrims reversalTrims(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors, const CorrectionGrid& grid, int axis);
// A standing correction with each axis's forward and reverse trims as the controller applies
// them moving (linear between the nodes, the end values beyond): LinuxCNC's COMP_FILEs (each
// axis's own function), HEIDENHAIN's tables with their BACKLASH column, SINUMERIK's CEC tables
// by direction, ISG's bilateral LSEC beside its volumetric compensation.
DirectedCorrection directedCorrection(const CorrectionGrid& grid, const CommandCorrection& standing, const std::array<ReversalTrims, 3>& trims);
DirectedCorrection directedCorrection(const CorrectionGrid& grid, const OneAxisReduction& functions, const std::array<ReversalTrims, 3>& trims);
// The same trims each rounded to a multiple of `unit` (mm): what a format holding whole units writes.
std::array<ReversalTrims, 3> roundedTrims(std::array<ReversalTrims, 3> trims, double unit);

// An axis's reversal as two tables on its own command, in the machine's units (mm; degrees for a
// rotary axis): what the controller adds moving forward and moving backward beyond what it adds
// standing, at equidistant positions. The linear axes' from their trims at the grid's nodes, the
// rotary axes' from their own positioning; only axes whose tables are not all zero.
struct AxisReversalTable {
  std::string axis;  // the machine file's name
  int index = 0;     // into Machine::axes
  bool rotary = false, modulo = false;
  std::vector<double> positions, forward, reverse;
};
std::vector<AxisReversalTable> axisReversalTables(const Machine& machine, const CorrectionGrid& grid, const std::array<ReversalTrims, 3>& trims,
                                                  const std::vector<RotaryPositioning>& rotary);

// LinuxCNC [JOINT_n] COMP_FILE: "nominal forward reverse" per line (COMP_FILE_TYPE 1: trims,
// the correction added to the command; 0: the positions nominal + trim), at most 256 lines.
// From the function of the axis's own command and its reversal trims (LinuxCNC applies the
// forward column moving forward, the reverse column moving backward); throws when it has more
// than 256 nodes.
std::string linuxcncCompFile(const AxisFunction& function, const ReversalTrims& reversal, int type);
// The same for a rotary joint, in degrees: its own correction moving forward and backward.
std::string linuxcncCompFile(const RotaryPositioning& rotary, int type);

// Siemens SINUMERIK CEC (sag and angularity compensation) tables as the INI part program
// %_N_NC_CEC_INI: one table per one-axis function, $AN_CEC_INPUT_AXIS / _OUTPUT_AXIS named by the
// machine file's axis names, equidistant $AN_CEC_STEP from $AN_CEC_MIN to $AN_CEC_MAX (mm), the
// values $AN_CEC[t, N] in mm added to the output axis, both directions, ending with M17. Then
// each axis's reversal as two tables on its own command, $AN_CEC_DIRECTION 1 (the positive
// traversing direction) and -1 (the negative): "position-dependent backlash compensation can be
// implemented using two tables" (function manual K3, 03/2013, p. 249).
// `pose`: the other axes' positions the functions were taken at, stated in a comment.
std::string siemensCecTables(const std::vector<AxisFunction>& functions, const std::vector<AxisReversalTable>& reversal, const std::string& pose);

// Siemens SINUMERIK LEC (leadscrew and measuring-system error compensation) as the INI part
// program %_N_AX_EEC_INI: per axis, from the function of its own command, $AA_ENC_COMP[0, N, axis]
// on the first measuring system, equidistant from $AA_ENC_COMP_MIN to _MAX by _STEP (mm). The
// values are the error, the correction negated: a positive value moves the axis negative (808D
// function manual, LEC). Throws for a function of another axis's command. The rotary axes' own
// corrections follow, by the machine file's axis names, in degrees over their positions, modulo
// ($AA_ENC_COMP_IS_MODULO = 1, 0 to 360) for a continuous axis whose table repeats.
std::string siemensLecTables(const std::vector<AxisFunction>& ownAxes, const Machine& machine, const std::vector<RotaryPositioning>& rotary,
                             const std::string& pose);

}  // namespace mtacc
