#pragma once
// Seed 004 (L133, L284-290, O1): the interpolator's command of every axis is recorded in a run
// of its own, on a clock offset from the encoder and instrument run. The offset is estimated by
// least squares against the encoder trace and the command is moved onto the encoder clock.
#include <span>
#include <string>
#include <vector>

#include "mtacc/core/joint_matrix.hpp"
#include "mtacc/core/uniform_spline.hpp"

namespace mtacc {

// Channels sampled together at start + k * period (s); one vector of samples per channel.
struct SampledTrace {
  double start = 0.0;
  double period = 0.0;
  std::vector<std::vector<double>> channels;

  size_t samples() const { return channels.empty() ? 0 : channels.front().size(); }
  double end() const { return start + period * static_cast<double>(samples() - 1); }
};

struct ClockOffsetSearch {
  double lowest = -0.1, highest = 0.1;  // s: the offsets considered
  Interpolation interpolation = Interpolation::CubicSpline;
};

// The command sample stamped s belongs at encoder time s + offset. What the least squares find
// is the recording offset plus the part of the servo lag a pure delay can explain, (1 - k_ff) / Kv
// for a proportional loop with feed-forward (seed 004 §4): the decomposition's delta_c then holds
// the following error left after the best delay.
struct ClockOffset {
  double offset = 0.0;         // s
  double rmsMisfit = 0.0;      // RMS over axes and samples of (encoder - moved command) / the axis's spread
  size_t samplesCompared = 0;  // encoder samples inside the moved command's span
};

// Every channel is normalised by its encoder spread (standard deviation) so that mm and deg
// weigh alike; a channel that does not move is left out. The offset is searched over the
// window at the encoder period (at most 20 000 steps), then refined by Gauss-Newton on the
// interpolated traces to the misfit's minimum. Throws
// InvalidInput for traces with different channel counts, no moving channel, an empty
// window, or offsets whose overlap holds fewer than a quarter of the encoder samples.
ClockOffset estimateClockOffset(const SampledTrace& command, const SampledTrace& encoder, const ClockOffsetSearch& search = {});

// Times first + k * step (s), k = 0 .. count - 1: an instrument's clock.
struct EvenTimes {
  double first = 0.0, step = 0.0;
  size_t count = 0;
};

// The trace, with its clock moved by `offset`, at the given times: row k holds every channel at
// time k (the poses there, for a trace of axis positions). Throws InvalidInput when a time falls
// outside the moved trace's span.
JointMatrix resampleTrace(const SampledTrace& trace, double offset, const EvenTimes& times,
                          Interpolation interpolation = Interpolation::CubicSpline);
// The same into `out` (times.count rows, one column per channel).
void resampleTrace(const SampledTrace& trace, double offset, const EvenTimes& times, Eigen::Ref<JointMatrix> out,
                   Interpolation interpolation = Interpolation::CubicSpline);

}  // namespace mtacc
