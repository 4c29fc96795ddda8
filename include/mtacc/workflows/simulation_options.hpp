#pragma once
// The options of `simulate ballbar | rtest | plan`, declared once: each reads the common noise,
// seed and set-up errors and its own path, and runs the simulation.
#include "mtacc/core/option_schema.hpp"
#include "mtacc/workflows/measurement_runs.hpp"

namespace mtacc {

const OptionSchema& ballbarSimulationSchema();  // noise, seed, setup, output, tool_ball, plane, centre, radius, points, feed, pose,
                                                // one_direction, lag, backlash, spike, spike_time
const OptionSchema& rtestSimulationSchema();    // noise, seed, setup, output, tool_ball, axis, from, to, points, sphere, pose, probe
const OptionSchema& planSimulationSchema();     // noise, seed, setup, output, plan

// The runs simulated, and written to `output` when it is given (a file; a folder for a plan).
SimulationResult simulateBallbar(const MachineSetup& setup, const OptionValues& values);
SimulationResult simulateRTest(const MachineSetup& setup, const OptionValues& values);
SimulationResult simulatePlanRuns(const MachineSetup& setup, const OptionValues& values);

}  // namespace mtacc
