// The controllers' kinematic data sets along a 5-axis program (issue 45, item 2): the controller
// running the fitted LinuxCNC pins or SINUMERIK toolholder data set, the workpiece probed, on a
// machine whose errors the data set carries: the TCP lands where the nominal machine puts it.
#include <gtest/gtest.h>

#include "mtacc/compensation/linuxcnc_kinematics.hpp"
#include "mtacc/compensation/siemens_toolholder.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/io/gcode_program.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {
namespace {

TableResidual alongThePath(const std::string& machine, const std::string& errors,
                           const std::function<CommandCorrection(const std::shared_ptr<const Machine>&, const ErrorModel&)>& controller) {
  const auto setup = loadMachineSetup({machine, "", "", std::nullopt, ""});
  const ErrorModel carried = parseErrors(*setup.machine, "errors: {" + errors + "}\n", "carried.yaml");
  const GcodeProgram program = parseGcodeProgram("G1 X100 Y50 Z100 B0 C0 F1000\nG1 X-50 Y20 Z80 B40 C90\nG1 X20 Y-60 Z120 B-60 C-135\n",
                                                 "path.nc", *setup.machine);
  const CorrectionGrid grid = correctionGrid(setup.machine, carried, CorrectionGridSpec{{3, 3, 3}, {}, 1});
  const TableResidual along = tableResidualAlong(setup.machine, carried, program, grid, controller(setup.machine, carried));
  EXPECT_EQ(along.samples, 3 * 17);
  return along;
}

TEST(ControllerKinematics, LinuxcncAlongAProgramLeavesWhatThePinsLeave) {
  const TableResidual along = alongThePath("double-pivot-head", "Z0C1: 7 um, X0X: 4 um", [](const auto& machine, const ErrorModel& errors) {
    return linuxcncCorrection(machine, fitLinuxcncKinematics(machine, errors));
  });
  EXPECT_GT(along.beforeMax, 4e-3);
  EXPECT_LT(along.afterMax, 1e-5);
}

TEST(ControllerKinematics, SinumerikAlongAProgramLeavesWhatTheDataSetLeaves) {
  const TableResidual along = alongThePath("swivel-head-table", "X0C: 5 um, Z0C1: 7 um, A0B: 15 urad", [](const auto& machine, const ErrorModel& errors) {
    return siemensToolholderCorrection(machine, fitSiemensToolholder(machine, errors));
  });
  EXPECT_GT(along.beforeMax, 4e-3);
  EXPECT_LT(along.afterMax, 1e-5);
}

}  // namespace
}  // namespace mtacc
