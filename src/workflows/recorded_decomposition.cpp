#include "mtacc/workflows/recorded_decomposition.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>
#include <utility>

#include "mtacc/io/recorded_signal.hpp"
#include "mtacc/workflows/tcp_uncertainty.hpp"

namespace mtacc {

namespace {

void degreesToRadians(const Machine& machine, SampledTrace& trace) {
  for (size_t a = 0; a < trace.channels.size(); ++a)
    for (double& v : trace.channels[a]) v *= machine.axes[a].fileUnit();
}

AlignedTest alignedTest(const MachineSetup& setup, const DecompositionSet& set, const RecordedTest& recorded) {
  const auto& machine = *setup.machine;
  const auto axes = machine.commandedAxisNames();
  const auto commandFile = readRecordedSignal(recorded.command, {axes, set.ncPeriod});
  const auto encoderFile = readRecordedSignal(recorded.encoder, {axes, set.ncPeriod > 0 ? set.ncPeriod : commandFile.trace.period});
  auto instrumentFile = readRecordedSignal(recorded.instrument, {{"dx_um", "dy_um", "dz_um"}, set.instrumentPeriod});
  auto command = commandFile.trace, encoder = encoderFile.trace;
  degreesToRadians(machine, command);
  degreesToRadians(machine, encoder);
  for (auto& channel : instrumentFile.trace.channels)
    for (double& v : channel) v *= kMicro;
  const SignalProcessing processing{set.clockOffset, {set.searchLowest, set.searchHighest, set.interpolation}, set.ball};
  try {
    return alignRecordedTest(setup.nominal(), setup.actual(), {recorded.feed, command, encoder, instrumentFile.trace}, processing);
  } catch (const InvalidInput& e) {
    const bool offset = std::string_view(e.what()).starts_with("clock offset");
    throw InputError({offset ? recorded.encoder : recorded.instrument, offset ? encoderFile.headerLine : instrumentFile.headerLine, "time_s"},
                     e.what());
  }
}

}  // namespace

const OptionSchema& decompositionSchema() {
  static const OptionSchema schema{
      "decompose",
      {{.key = "set", .kind = OptionKind::Text, .help = "decomposition set (YAML, docs/file-formats.md \"Decomposition sets\")", .positional = true},
       {.key = "series", .kind = OptionKind::Count,
        .help = "with --json: each test's contributions along the normalised path u, at most this many points (every k-th sample)",
        .defaultText = "0", .low = 0, .high = 10000000, .outOfRange = "must be from 0 to 10000000"},
       {"drift_frame", OptionKind::Text,
        "where the drift is constant over a test: machine (Andolfatto et al. 2011's, the default) or workpiece; overrides the set's drift_frame"}}};
  return schema;
}

DecompositionRequest decompositionRequest(const OptionValues& values) {
  const OptionReader read(decompositionSchema(), values);
  return {*read.text("set"), read.text("drift_frame"), static_cast<size_t>(*read.count("series"))};
}

DecompositionSet loadDecompositionSet(const DecompositionRequest& request) {
  std::optional<DriftFrame> frame;
  if (request.driftFrame) frame = parseDriftFrame(*request.driftFrame, InputLocation{"", 0, "drift_frame"});
  auto set = loadDecompositionSet(request.set);
  if (frame) set.driftFrame = *frame;
  return set;
}

RecordedDecomposition decomposeRecordedSet(const MachineSetup& setup, const DecompositionSet& set) {
  RecordedDecomposition out;
  out.set = set;
  if (setup.covariance) {
    for (const auto& p : setup.covariance->parameters) out.linkParameters.push_back(p.name);
    out.linkLeftOut = setup.covariance->leftOut;
  }
  std::vector<DecompositionTest> tests;
  for (const auto& recorded : set.tests) {
    auto aligned = alignedTest(setup, set, recorded);
    auto& u = out.pathFraction.emplace_back(aligned.test.path);
    const double length = u.back() - u.front();
    for (double& v : u) v = length > 0 ? (v - aligned.test.path.front()) / length : 0.0;
    const auto& a = aligned.alignment;
    if (a.atSearchLimit)
      out.warnings.push_back(fmt::format(
          "{} mm/min: the clock offset estimated, {:.3f} ms, lies at the end of the search window [{:g}, {:g}] ms: the best offset "
          "may lie beyond it, and the contouring error it sets is then wrong; widen search_ms or state clock_offset_ms",
          recorded.feed, a.offset * 1e3, set.searchLowest * 1e3, set.searchHighest * 1e3));
    constexpr double kWorstMisfit = 0.01;  // of the axes' spreads: 1e-5 to 4e-4 where command and encoder are of one run
    if (a.estimated && !a.atSearchLimit && a.rmsMisfit > kWorstMisfit)
      out.warnings.push_back(fmt::format(
          "{} mm/min: the command and encoder traces do not line up at any offset of the search window: at the best, {:.3f} ms, they differ by {:.2g} % of the "
          "axes' spread (RMS), where one run's traces differ by hundredths of a percent; are they of the same run and program?",
          recorded.feed, a.offset * 1e3, a.rmsMisfit * 100));
    if (a.tracesOffset) {
      constexpr double kLeadAllowed = 1e-3;  // s: the encoder cannot lead the command; 1 ms for the estimate's own scatter
      const double lag = *a.tracesOffset - a.offset;
      if (lag < -kLeadAllowed || lag > set.largestLag)
        out.warnings.push_back(fmt::format(
            "{} mm/min: the command and encoder traces line up best at {:.3f} ms, {:.3f} ms {} the stated clock_offset_ms {:.3f}: {}; "
            "the stated offset is likely wrong, and the contouring error it sets with it (leave clock_offset_ms out to estimate it)",
            recorded.feed, *a.tracesOffset * 1e3, std::abs(lag) * 1e3, lag < 0 ? "before" : "after", a.offset * 1e3,
            lag < 0 ? "the encoder would lead the command" : fmt::format("more servo lag than largest_lag_ms ({:g} ms) allows", set.largestLag * 1e3)));
    }
    if (!a.instrumentSpikes.empty())
      out.warnings.push_back(fmt::format(
          "{} mm/min: {} instrument sample(s) of {} stand out from their neighbours by more than 8 robust standard deviations "
          "(samples counted from 0: {}{}): a spike or a lost sample enters the dynamic error as if the machine had moved so",
          recorded.feed, a.instrumentSpikes.size(), recorded.instrument,
          fmt::join(a.instrumentSpikes.begin(), a.instrumentSpikes.begin() + static_cast<std::ptrdiff_t>(std::min<size_t>(5, a.instrumentSpikes.size())), ", "),
          a.instrumentSpikes.size() > 5 ? ", ..." : ""));
    if (setup.covariance) out.linkUncertainty.push_back(directionStatistics(tcpUncertainty(setup, aligned.encoderPoses.matrix())));
    tests.push_back(std::move(aligned.test));
    out.alignment.push_back(aligned.alignment);
  }
  try {
    out.tests = decomposeErrors(std::move(tests), {set.referenceTest, set.degree, set.parameter, set.driftFrame, set.referenceFit});
  } catch (const InvalidInput& e) {
    throw InputError({set.file, set.tests[static_cast<size_t>(set.referenceTest)].line, fmt::format("tests[{}]", set.referenceTest)}, e.what());
  }
  std::array<std::vector<double>, 3> rms;
  std::vector<double> feeds;
  for (const auto& test : out.tests) {
    out.shares.push_back(decompositionShares(test));
    out.contouring.push_back(directionStatistics(test.contouring));
    out.contouringOrthogonal.push_back(directionStatistics(test.contouringOrthogonal));
    LargeVector<Vec3> quasiStatic(test.motion.size());
    for (size_t i = 0; i < quasiStatic.size(); ++i) quasiStatic[i] = test.quasiStatic(i);
    out.quasiStatic.push_back(directionStatistics(quasiStatic));
    out.dynamic.push_back(directionStatistics(test.dynamic));
    feeds.push_back(test.recorded.feed);
    for (int d = 0; d < 3; ++d) rms[static_cast<size_t>(d)].push_back(out.dynamic.back().rms[d]);
  }
  for (size_t d = 0; d < 3; ++d) {
    try {
      out.dynamicLaw[d] = fitPowerLaw(feeds, rms[d]);
    } catch (const InvalidInput&) {
      out.dynamicLaw[d].reset();  // fewer than two feeds or an RMS of zero: no law to state
    }
  }
  return out;
}

namespace {

// Every k-th sample of each contribution along u, in um per direction.
nlohmann::json seriesJson(const DecomposedTest& test, std::span<const double> u, size_t points) {
  const size_t stride = std::max<size_t>(1, (u.size() + points - 1) / points);
  nlohmann::json j{{"stride", stride}, {"u", nlohmann::json::array()}};
  for (size_t i = 0; i < u.size(); i += stride) j["u"].push_back(u[i]);
  const std::pair<const char*, const LargeVector<Vec3>*> contributions[] = {
      {"contouring_um", &test.contouring}, {"link_um", &test.recorded.link}, {"motion_um", &test.motion}, {"dynamic_um", &test.dynamic}};
  for (const auto& [name, series] : contributions)
    for (int d = 0; d < 3; ++d) {
      auto& values = j[name][std::string(1, "xyz"[d])] = nlohmann::json::array();
      for (size_t i = 0; i < series->size(); i += stride) values.push_back((*series)[i][d] * 1e3);
    }
  return j;
}

}  // namespace

nlohmann::json toJson(const RecordedDecomposition& r, size_t seriesPoints) {
  const auto um = [](const Vec3& v) { return nlohmann::json::array({v.x() * 1e3, v.y() * 1e3, v.z() * 1e3}); };
  nlohmann::json j;
  j["reference_feed_mm_per_min"] = r.tests[static_cast<size_t>(r.set.referenceTest)].recorded.feed;
  j["degree"] = r.set.degree;
  j["parameter"] = r.set.parameter == MotionParameter::Path ? "path" : "time";
  j["interpolation"] = r.set.interpolation == Interpolation::CubicSpline ? "cubic" : "linear";
  j["reference_fit"] = r.set.referenceFit == ReferenceFit::Steady ? "steady" : "all";
  j["reference_samples_left_out"] = r.tests[static_cast<size_t>(r.set.referenceTest)].leftOutOfFit;
  j["tests"] = nlohmann::json::array();
  for (size_t k = 0; k < r.tests.size(); ++k) {
    const auto& a = r.alignment[k];
    const auto& s = r.shares[k];
    j["tests"].push_back({
        {"feed_mm_per_min", r.tests[k].recorded.feed},
        {"clock_offset_ms", a.offset * 1e3},
        {"clock_offset_estimated", a.estimated},
        {"alignment_rms_misfit", a.rmsMisfit},
        {"instrument_samples", a.instrumentSamples},
        {"samples_used", a.samplesUsed},
        {"first_sample_used", a.firstSampleUsed},
        {"clock_offset_at_search_limit", a.atSearchLimit},
        {"clock_offset_traces_ms", a.tracesOffset ? nlohmann::json(*a.tracesOffset * 1e3) : nlohmann::json(nullptr)},
        {"instrument_spikes", a.instrumentSpikes},
        {"drift_um", um(r.tests[k].drift)},
        {"shares_percent",
         {{"contouring", s.contouring}, {"quasi_static", s.quasiStatic}, {"dynamic", s.dynamic}}},
        {"split_shares_percent",
         {{"contouring", s.splitContouring}, {"link", s.link}, {"motion", s.motion}, {"drift", s.drift}, {"dynamic", s.splitDynamic},
          {"over_printed_denominator", s.splitOverPrinted}}},
        {"contouring_max_um", um(r.contouring[k].maximum)},
        {"contouring_orthogonal_max_um", um(r.contouringOrthogonal[k].maximum)},
        {"contouring_orthogonal_undefined_samples", r.tests[k].orthogonalUndefined},
        {"quasi_static_max_um", um(r.quasiStatic[k].maximum)},
        {"dynamic_max_um", um(r.dynamic[k].maximum)},
        {"dynamic_rms_um", um(r.dynamic[k].rms)},
    });
    if (!r.linkUncertainty.empty())
      j["tests"].back()["link_uncertainty_um"] = {{"max", um(r.linkUncertainty[k].maximum)}, {"rms", um(r.linkUncertainty[k].rms)}};
    if (seriesPoints > 0) j["tests"].back()["series"] = seriesJson(r.tests[k], r.pathFraction[k], seriesPoints);
  }
  j["link_uncertainty"] = r.linkUncertainty.empty() ? nlohmann::json(nullptr)
                                                    : nlohmann::json{{"k", 1}, {"parameters", r.linkParameters}, {"left_out", r.linkLeftOut}};
  j["warnings"] = r.warnings;
  j["drift_frame"] = r.set.driftFrame == DriftFrame::Machine ? "machine" : "workpiece";
  j["dynamic_rms_power_law"] = nlohmann::json::object();
  for (size_t d = 0; d < 3; ++d)
    if (const auto& law = r.dynamicLaw[d])
      j["dynamic_rms_power_law"][std::string(1, "xyz"[d])] = {
          {"kappa_um", law->kappa * 1e3}, {"exponent", law->exponent}, {"largest_relative_misfit", law->largestRelativeMisfit}};
  return j;
}

}  // namespace mtacc
