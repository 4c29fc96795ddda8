#pragma once
// Seed 004 eqs. 3-9 and 13-15 on one test's signals: the command trace moved onto the encoder
// clock (O1), both traces resampled at the instrument's samples (O7), chi_nom and chi_enc by the
// nominal direct kinematics, and the link errors of the identified model along the encoder path.
#include <optional>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/procedures/error_decomposition.hpp"
#include "mtacc/procedures/trace_alignment.hpp"

namespace mtacc {

struct TestAlignment {
  double offset = 0.0;     // s: the command sample stamped s belongs at encoder time s + offset
  bool estimated = false;
  double rmsMisfit = 0.0;  // of the estimate, in the axes' spreads (0 when given)
  size_t instrumentSamples = 0, samplesUsed = 0;  // those outside the command's motion or the encoder trace are left out
  size_t firstSampleUsed = 0;                     // the used ones are consecutive from this instrument sample on
  // An estimate within one scan step of an end of the search window: the misfit may fall
  // further beyond it, and the offset (with the contouring error it sets) cannot be trusted.
  bool atSearchLimit = false;
  std::vector<size_t> instrumentSpikes;  // instrument samples that stand out from their neighbours (spikeSamples)
  // With a stated offset: where the traces line up best in the search window (the offset plus
  // the servo lag a pure delay explains); absent when they cannot be lined up there.
  std::optional<double> tracesOffset;
};

struct RecordedSignals {
  double feed = 0.0;              // mm/min as programmed
  const SampledTrace& command;    // commanded axes (mm, rad) on the NC's clock
  const SampledTrace& encoder;    // the same axes' encoder positions on the instrument's clock
  const SampledTrace& instrument; // tool ball minus workpiece ball, workpiece frame, mm
};

struct SignalProcessing {
  std::optional<double> clockOffset;  // s; estimated when absent
  ClockOffsetSearch search;           // its window and the interpolation of every trace
  Vec3 ball = Vec3::Zero();           // the workpiece ball centre, workpiece frame, mm
};

struct AlignedTest {
  DecompositionTest test;
  TestAlignment alignment;
  LargeJointMatrix encoderPoses;  // the encoder positions at the test's samples (mm, rad), a row each
};

// The test runs from the command's departure (its last sample at rest at the start) to its
// arrival (its first sample at rest at the end), moved onto the encoder clock: the dwells before
// and after are left out, so that the normalised time of eq. 17 means the same point of the path
// at every feed (O5). `identified`: the machine with its identified link errors (delta_l = its
// TCP minus the nominal TCP at the encoder positions). Throws InvalidInput when the offset cannot be
// estimated (see estimateClockOffset) or fewer than four instrument samples fall inside the
// moved motion and the encoder trace.
AlignedTest alignRecordedTest(const KinematicModel& nominal, const KinematicModel& identified, const RecordedSignals& signals,
                              const SignalProcessing& processing, int threads = kAllCores);

}  // namespace mtacc
