#include "mtacc/virtual_controller/virtual_recording.hpp"

#include <cmath>
#include <random>

#include "mtacc/core/input_error.hpp"
#include "mtacc/dynamics/transient_deflection.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

namespace {

// The structure's deflection (mm, machine frame) under the accelerations of the machine's linear
// axes that share a name with a structure axis, assembled at the positions of the middle sample.
std::vector<Vec3> deflection(const StructureModel& structure, const Machine& machine, const SampledTrace& axes) {
  const size_t n = axes.samples();
  std::vector<std::vector<double>> accelerations(structure.axes.size());
  std::vector<double> positions(structure.axes.size(), 0.0);
  for (size_t j = 0; j < structure.axes.size(); ++j)
    for (size_t a = 0; a < axes.channels.size(); ++a) {
      if (machine.axes[a].name != structure.axes[j].name || machine.axes[a].isRotary()) continue;
      const auto& x = axes.channels[a];
      positions[j] = x[n / 2] * 1e-3;
      auto& acceleration = accelerations[j];
      acceleration.assign(n, 0.0);
      for (size_t k = 1; k + 1 < n; ++k) acceleration[k] = (x[k + 1] - 2 * x[k] + x[k - 1]) / (axes.period * axes.period) * 1e-3;
    }
  auto displacement = accelerationDeflection(structure, positions, accelerations, axes.period);
  for (auto& d : displacement) d *= 1e3;
  if (displacement.empty()) displacement.assign(n, Vec3::Zero());
  return displacement;
}

}  // namespace

VirtualRecording recordVirtualTest(const KinematicModel& nominal, const KinematicModel& actual, const SampledTrace& reference,
                                   const VirtualRecordingOptions& options, int threads) {
  const auto& machine = *nominal.machine;
  const size_t axisCount = reference.channels.size(), n = reference.samples();
  if (!options.servo.empty() && options.servo.size() != axisCount)
    throw InvalidInput("virtual recording: one servo loop per commanded axis");
  const double ratio = options.ncPeriod / reference.period;
  const auto every = static_cast<size_t>(std::llround(ratio));
  if (!(every >= 1 && std::fabs(ratio - static_cast<double>(every)) < 1e-9 * ratio))
    throw InvalidInput("virtual recording: the NC period must be a whole multiple of the reference's period");
  if (!(options.noise >= 0.0) || !std::isfinite(options.noise)) throw InvalidInput("virtual recording: the noise must be finite and not negative");

  VirtualRecording out;
  SampledTrace axes{reference.start, reference.period, {}};
  for (size_t a = 0; a < axisCount; ++a)
    axes.channels.push_back(options.servo.empty() ? reference.channels[a] : followCommand(reference.channels[a], reference.period, options.servo[a]));

  out.encoder = {reference.start, options.ncPeriod, std::vector<std::vector<double>>(axisCount)};
  for (size_t a = 0; a < axisCount; ++a)
    for (size_t k = 0; k < n; k += every) out.encoder.channels[a].push_back(axes.channels[a][k]);

  const double firstStamp = std::ceil((reference.start - options.clockOffset) / options.ncPeriod - 1e-9) * options.ncPeriod;
  const auto commandSamples = static_cast<long>(std::floor((reference.end() - options.clockOffset - firstStamp) / options.ncPeriod + 1e-9)) + 1;
  if (commandSamples < 4) throw InvalidInput("virtual recording: the clock offset leaves fewer than four command samples");
  out.command = {firstStamp, options.ncPeriod, {}};
  for (size_t a = 0; a < axisCount; ++a) {
    const UniformSpline spline(reference.start, reference.period, reference.channels[a]);
    auto& channel = out.command.channels.emplace_back(static_cast<size_t>(commandSamples));
    for (long j = 0; j < commandSamples; ++j) channel[static_cast<size_t>(j)] = spline(firstStamp + static_cast<double>(j) * options.ncPeriod + options.clockOffset);
  }

  const auto q = posesFromChannels(axes.channels);
  const PointMatrix atAxes = toolPositions(nominal, q, threads), withErrors = toolPositions(actual, q, threads);
  const PointMatrix atReference = toolPositions(nominal, posesFromChannels(reference.channels), threads);
  const auto deflected = options.structure ? deflection(*options.structure, machine, axes) : std::vector<Vec3>(n, Vec3::Zero());
  std::mt19937_64 random(options.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  out.instrument = {reference.start, reference.period, std::vector<std::vector<double>>(3, std::vector<double>(n))};
  out.contouring.resize(n);
  out.geometric.resize(n);
  out.dynamic.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const auto i = static_cast<long>(k);
    out.contouring[k] = (atAxes.row(i) - atReference.row(i)).transpose();
    out.geometric[k] = (withErrors.row(i) - atAxes.row(i)).transpose();
    const Mat3 toWorkpiece = workpiecePose(nominal, q.row(i).data(), nullptr).linear().transpose();
    out.dynamic[k] = toWorkpiece * deflected[k];
    const Vec3 drift = options.driftFrame == DriftFrame::Machine ? Vec3(toWorkpiece * options.drift) : options.drift;
    const Vec3 reading = withErrors.row(i).transpose() - options.ball + drift + out.dynamic[k] +
                         options.noise * Vec3(noise(random), noise(random), noise(random));
    for (int c = 0; c < 3; ++c) out.instrument.channels[static_cast<size_t>(c)][k] = reading[c];
  }
  return out;
}

}  // namespace mtacc
