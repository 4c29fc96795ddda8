#pragma once
// The virtual machine's recording of one test (seed 004 §4, extraction §14.1): the axes follow
// the interpolator's reference through their servo loops; the NC records the command on a
// clock of its own and the encoder positions every NC cycle; the instrument reads the tool
// relative to its workpiece ball at the reference's rate, on the encoder's clock, with the
// machine's geometric errors, a thermal drift, the structure's deflection under the axes'
// accelerations, and white noise. The truth of each contribution is kept.
#include <cstdint>
#include <vector>

#include "mtacc/core/parallel.hpp"
#include "mtacc/dynamics/structure.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/procedures/error_decomposition.hpp"
#include "mtacc/virtual_controller/servo_loop.hpp"
#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

struct VirtualRecordingOptions {
  std::vector<ServoGains> servo;  // per commanded axis; empty: every axis follows exactly
  double ncPeriod = 0.003;        // s: a whole multiple of the reference's period
  double clockOffset = 0.018;     // s: the command sample stamped s is the reference at encoder time s + clockOffset
  Vec3 ball = Vec3::Zero();       // the instrument's workpiece ball centre, workpiece frame, mm
  Vec3 drift = Vec3::Zero();      // mm, in every reading of the test, constant in driftFrame
  DriftFrame driftFrame = DriftFrame::Machine;
  double noise = 2e-4;            // mm: standard deviation of each reading component
  std::uint64_t seed = 1;
  const StructureModel* structure = nullptr;  // deflection under the accelerations of its axes (by name); none when null
};

struct VirtualRecording {
  SampledTrace command, encoder;  // every NC cycle, mm and rad
  SampledTrace instrument;        // tool ball minus workpiece ball, workpiece frame, mm, at the reference's rate
  // The truth at each instrument sample, mm, workpiece frame:
  std::vector<Vec3> contouring;   // nominal TCP at the axes' positions minus at the reference
  std::vector<Vec3> geometric;    // TCP of the machine with its errors minus the nominal TCP, at the axes' positions
  std::vector<Vec3> dynamic;      // the structure's deflection
};

// `reference`: the interpolator's output (mm, rad) from time 0. Throws InvalidInput for a
// servo list of the wrong length, an NC period that is not a whole multiple of the reference's,
// a clock offset that leaves fewer than four command samples, or a negative noise; InputError
// from the structure as accelerationDeflection does.
VirtualRecording recordVirtualTest(const KinematicModel& nominal, const KinematicModel& actual, const SampledTrace& reference,
                                   const VirtualRecordingOptions& options, int threads = kAllCores);

}  // namespace mtacc
