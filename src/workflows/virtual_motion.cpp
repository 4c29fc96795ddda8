#include "mtacc/workflows/virtual_motion.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "mtacc/io/gcode_program.hpp"
#include "mtacc/io/recorded_signal.hpp"
#include "mtacc/io/structure_yaml.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

namespace {

constexpr int kPointsPerArc = 64;

// The program's moves as points: each straight move's end, an arc every 1/64 of its sweep.
std::vector<std::vector<double>> programPath(const GcodeProgram& program) {
  std::vector<std::vector<double>> path;
  for (const auto& move : program.moves) {
    if (path.empty()) path.emplace_back(move.from.begin(), move.from.end());
    if (move.isArc())
      for (int i = 1; i <= kPointsPerArc; ++i) path.push_back(move.at(static_cast<double>(i) / kPointsPerArc));
    else
      path.emplace_back(move.to.begin(), move.to.end());
  }
  return path;
}

Vec3 largestComponents(const std::vector<Vec3>& series) {
  Vec3 largest = Vec3::Zero();
  for (const auto& v : series) largest = largest.cwiseMax(v.cwiseAbs());
  return largest;
}

std::vector<double> perAxis(const std::vector<double>& values, const std::vector<std::string>& axes, const std::string& key) {
  if (values.size() == 1) return std::vector<double>(axes.size(), values[0]);
  if (values.size() != axes.size())
    throw InputError({"", 0, key}, fmt::format("{} values; give one for every axis or one per axis ({})", values.size(), fmt::join(axes, ", ")));
  return values;
}

}  // namespace

const OptionSchema& motionSimulationSchema() {
  static const OptionSchema schema{
      "simulate motion",
      {{.key = "program", .kind = OptionKind::Text, .help = "NC program (G-code) in axis positions; its F words are replaced by each feed",
        .required = true},
       {.key = "output", .kind = OptionKind::Text, .help = "Directory to write the signal files and set.yaml into", .required = true},
       {.key = "feeds", .kind = OptionKind::Numbers, .help = "feeds in mm/min (FGROUP: mm and deg on one path length)",
        .defaultText = "1000,1800,3240,5832,10498,18896", .low = 1e-3, .high = 1e6, .outOfRange = "each must be from 0.001 to 1e6 mm/min"},
       {"structure", OptionKind::Text, "structure model (YAML or bundled name, e.g. wcayfxzt-compact) for the dynamic error"},
       {.key = "noise", .kind = OptionKind::Quantity, .help = "Standard deviation of the instrument's noise per component", .defaultText = "0.2 um",
        .low = 0, .high = 1, .outOfRange = "must be from 0 to 1 mm"},
       {.key = "seed", .kind = OptionKind::Count, .help = "Random seed of the noise", .defaultText = "1", .low = 0, .high = 2147483647,
        .outOfRange = "must be from 0 to 2147483647"},
       {.key = "acceleration", .kind = OptionKind::Number, .help = "interpolator's acceleration limit, path units/s^2", .defaultText = "3000",
        .low = 1e-3, .high = 1e7, .outOfRange = "must be from 0.001 to 1e7"},
       {.key = "jerk_time_ms", .kind = OptionKind::Number, .help = "moving-average filter of the interpolator, ms", .defaultText = "20", .low = 0,
        .high = 1000, .outOfRange = "must be from 0 to 1000 ms"},
       {.key = "kv", .kind = OptionKind::Numbers, .help = "position loop gain, 1/s: one for every axis or one per axis, e.g. 40,45,50,35,30",
        .defaultText = "40", .low = 1e-3, .high = 1e4, .outOfRange = "each must be from 0.001 to 10000 1/s"},
       {.key = "feed_forward", .kind = OptionKind::Numbers, .help = "velocity feed-forward, 0..1: one for every axis or one per axis",
        .defaultText = "0.99", .low = 0, .high = 1, .outOfRange = "each must be from 0 to 1"},
       {"format", OptionKind::Text, "signal files: csv or npy (NumPy structured arrays)", "csv"},
       {.key = "clock_offset_ms", .kind = OptionKind::Number, .help = "offset of the command recording's clock, ms", .defaultText = "18",
        .low = -1e4, .high = 1e4, .outOfRange = "must be from -10000 to 10000 ms"}}};
  return schema;
}

MotionSimulationRequest motionSimulationRequest(const OptionValues& values) {
  const OptionReader read(motionSimulationSchema(), values);
  MotionSimulationRequest r;
  r.program = *read.text("program");
  r.folder = *read.text("output");
  r.feeds = read.numbers("feeds");
  r.structure = read.text("structure").value_or("");
  r.noise = *read.quantity("noise");
  r.seed = static_cast<std::uint64_t>(*read.count("seed"));
  r.limits.acceleration = *read.number("acceleration");
  r.limits.jerkTime = *read.number("jerk_time_ms") * 1e-3;
  r.positionGains = read.numbers("kv");
  r.feedForwards = read.numbers("feed_forward");
  r.format = signalFormatNamed(*read.text("format"), "format");
  r.clockOffset = *read.number("clock_offset_ms") * 1e-3;
  return r;
}

MotionSimulationResult simulateMotion(const MachineSetup& setup, const MotionSimulationRequest& request) {
  const auto& machine = *setup.machine;
  const auto program = readGcodeProgram(request.program, machine);
  const auto path = programPath(program);
  if (path.size() < 2) throw InputError({request.program, 0, ""}, "the program has no move");
  const auto axes = machine.commandedAxisNames();
  std::vector<bool> rotary;
  std::vector<double> scales;
  for (size_t a = 0; a < axes.size(); ++a) {
    rotary.push_back(machine.axes[a].isRotary());
    scales.push_back(1.0 / machine.axes[a].fileUnit());
  }
  const auto gains = perAxis(request.positionGains, axes, "kv"), feedForwards = perAxis(request.feedForwards, axes, "feed_forward");
  std::vector<ServoGains> servo;
  for (size_t a = 0; a < axes.size(); ++a) servo.push_back({gains[a], feedForwards[a]});
  const auto nominal = setup.nominal(), actual = setup.actual();
  std::unique_ptr<StructureModel> structure;
  if (!request.structure.empty()) structure = std::make_unique<StructureModel>(loadStructure(request.structure));

  MotionSimulationResult out;
  out.ball = request.ball ? *request.ball : toolPosition(nominal, path.front().data());
  std::filesystem::create_directories(request.folder);
  std::string set = fmt::format("# written by mtacc simulate motion from {}\nball: [{:.9g} mm, {:.9g} mm, {:.9g} mm]\nnc_rate_hz: {:.9g}\n"
                                "instrument_rate_hz: {:.9g}\ntests:\n",
                                request.program, out.ball.x(), out.ball.y(), out.ball.z(), 1.0 / request.ncPeriod, 1.0 / request.instrumentPeriod);
  for (size_t k = 0; k < request.feeds.size(); ++k) {
    const double feed = request.feeds[k];
    VirtualRecordingOptions options;
    options.servo = servo;
    options.ncPeriod = request.ncPeriod;
    options.clockOffset = request.clockOffset;
    options.ball = out.ball;
    options.drift = static_cast<double>(k) * request.driftStep;
    options.noise = request.noise;
    options.seed = request.seed + k;
    options.structure = structure.get();
    VirtualRecording recording;
    try {
      recording = recordVirtualTest(nominal, actual, interpolateMotion(path, rotary, feed, request.limits, request.instrumentPeriod), options);
    } catch (const InvalidInput& e) {
      throw InputError({request.program, 0, fmt::format("feed {:g}", feed)}, e.what());
    }
    SimulatedFeed simulated{feed, recording.instrument.end() - recording.instrument.start, recording.instrument.samples(),
                            largestComponents(recording.contouring), largestComponents(recording.geometric),
                            largestComponents(recording.dynamic), {}};
    SampledTrace truth{recording.instrument.start, recording.instrument.period, {}};
    for (const auto* series : {&recording.contouring, &recording.geometric, &recording.dynamic})
      for (int c = 0; c < 3; ++c) {
        auto& channel = truth.channels.emplace_back(series->size());
        for (size_t i = 0; i < series->size(); ++i) channel[i] = (*series)[i][c];
      }
    const std::string stem = fmt::format("f{:.0f}", feed);
    const auto write = [&](const std::string& name, const std::string& text) {
      const auto file = (std::filesystem::path(request.folder) / fmt::format("{}-{}.{}", stem, name, extensionOf(request.format))).string();
      writeFileAtomically(file, text);
      simulated.files.push_back(file);
    };
    write("command", signalFile(request.format, recording.command, axes, scales));
    write("encoder", signalFile(request.format, recording.encoder, axes, scales));
    write("instrument", signalFile(request.format, recording.instrument, {"dx_um", "dy_um", "dz_um"}, {1e3, 1e3, 1e3}));
    write("truth", signalFile(request.format, truth,
                             {"contouring_x_um", "contouring_y_um", "contouring_z_um", "geometric_x_um", "geometric_y_um", "geometric_z_um",
                              "dynamic_x_um", "dynamic_y_um", "dynamic_z_um"},
                             std::vector<double>(9, 1e3)));
    const auto ext = extensionOf(request.format);
    set += fmt::format("  - {{feed: {:.9g}, command: {}-command.{}, encoder: {}-encoder.{}, instrument: {}-instrument.{}}}\n", feed, stem, ext, stem,
                       ext, stem, ext);
    out.feeds.push_back(std::move(simulated));
  }
  out.setFile = (std::filesystem::path(request.folder) / "set.yaml").string();
  writeFileAtomically(out.setFile, set);
  return out;
}

nlohmann::json toJson(const MotionSimulationResult& s) {
  const auto um = [](const Vec3& v) { return nlohmann::json::array({v.x() * 1e3, v.y() * 1e3, v.z() * 1e3}); };
  nlohmann::json j{{"ball_mm", {s.ball.x(), s.ball.y(), s.ball.z()}}, {"set", s.setFile}, {"feeds", nlohmann::json::array()}};
  for (const auto& f : s.feeds)
    j["feeds"].push_back({{"feed_mm_per_min", f.feed},
                          {"duration_s", f.duration},
                          {"instrument_samples", f.instrumentSamples},
                          {"contouring_max_um", um(f.contouringMax)},
                          {"geometric_max_um", um(f.geometricMax)},
                          {"dynamic_max_um", um(f.dynamicMax)},
                          {"files", f.files}});
  return j;
}

}  // namespace mtacc
