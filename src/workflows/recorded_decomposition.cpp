#include "mtacc/workflows/recorded_decomposition.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "mtacc/io/signal_csv.hpp"
#include "mtacc/kinematics/forward.hpp"

namespace mtacc {

namespace {

std::vector<std::string> commandedAxes(const Machine& machine) {
  std::vector<std::string> names;
  for (const auto& axis : machine.axes)
    if (axis.commanded()) names.push_back(axis.name);
  return names;
}

void degreesToRadians(const Machine& machine, SampledTrace& trace) {
  for (size_t a = 0; a < trace.channels.size(); ++a)
    if (machine.axes[a].isRotary())
      for (double& v : trace.channels[a]) v *= kDeg;
}

JointMatrix asPoses(const std::vector<std::vector<double>>& channels) {
  JointMatrix q(static_cast<long>(channels.front().size()), static_cast<long>(channels.size()));
  for (size_t a = 0; a < channels.size(); ++a)
    for (size_t k = 0; k < channels[a].size(); ++k) q(static_cast<long>(k), static_cast<long>(a)) = channels[a][k];
  return q;
}

std::vector<Vec3> relativeToBall(const PointMatrix& tcp, const Vec3& ball) {
  std::vector<Vec3> out(static_cast<size_t>(tcp.rows()));
  for (long k = 0; k < tcp.rows(); ++k) out[static_cast<size_t>(k)] = tcp.row(k).transpose() - ball;
  return out;
}

DecompositionTest alignedTest(const MachineSetup& setup, const DecompositionSet& set, const RecordedTest& recorded, TestAlignment& alignment) {
  const auto& machine = *setup.machine;
  const auto axes = commandedAxes(machine);
  auto command = readSignalCsv(recorded.command, {axes, set.ncPeriod}).trace;
  const auto encoderFile = readSignalCsv(recorded.encoder, {axes, set.ncPeriod > 0 ? set.ncPeriod : command.period});
  const auto instrumentFile = readSignalCsv(recorded.instrument, {{"dx_um", "dy_um", "dz_um"}, set.instrumentPeriod});
  auto encoder = encoderFile.trace;
  const auto& instrument = instrumentFile.trace;
  degreesToRadians(machine, command);
  degreesToRadians(machine, encoder);

  if (set.clockOffset) {
    alignment.offset = *set.clockOffset;
  } else {
    try {
      const auto found = estimateClockOffset(command, encoder, {set.searchLowest, set.searchHighest, set.interpolation});
      alignment = {found.offset, true, found.rmsMisfit, 0, 0};
    } catch (const std::invalid_argument& e) {
      throw InputError({recorded.encoder, encoderFile.headerLine, "time_s"}, e.what());
    }
  }
  alignment.instrumentSamples = instrument.samples();
  const double from = std::max(command.start + alignment.offset, encoder.start), to = std::min(command.end() + alignment.offset, encoder.end());
  DecompositionTest test;
  test.feed = recorded.feed;
  std::vector<size_t> used;
  for (size_t j = 0; j < instrument.samples(); ++j) {
    const double t = instrument.start + instrument.period * static_cast<double>(j);
    if (t >= from && t <= to) {
      test.time.push_back(t);
      used.push_back(j);
    }
  }
  alignment.samplesUsed = used.size();
  if (used.size() < 4)
    throw InputError({recorded.instrument, instrumentFile.headerLine, "time_s"},
                     fmt::format("{} instrument samples fall inside the command and encoder traces (offset {:.3f} ms)", used.size(),
                                 alignment.offset * 1e3));
  const auto nominalQ = asPoses(resampleTrace(command, alignment.offset, test.time, set.interpolation));
  const auto encoderQ = asPoses(resampleTrace(encoder, 0.0, test.time, set.interpolation));
  const DirectionMatrix none;
  ToolPointBatch nominal, atEncoder, actual;
  const auto nominalModel = setup.nominal(), actualModel = setup.actual();
  toolPoints(nominalModel, {nominalQ, none}, nominal, 1);
  toolPoints(nominalModel, {encoderQ, none}, atEncoder, 1);
  toolPoints(actualModel, {encoderQ, none}, actual, 1);
  test.nominal = relativeToBall(nominal.positions, set.ball);
  test.encoder = relativeToBall(atEncoder.positions, set.ball);
  test.link.resize(used.size());
  test.measured.resize(used.size());
  for (size_t i = 0; i < used.size(); ++i) {
    const auto k = static_cast<long>(i);
    test.link[i] = (actual.positions.row(k) - atEncoder.positions.row(k)).transpose();
    test.measured[i] = kMicro * Vec3(instrument.channels[0][used[i]], instrument.channels[1][used[i]], instrument.channels[2][used[i]]);
  }
  return test;
}

}  // namespace

RecordedDecomposition decomposeRecordedSet(const MachineSetup& setup, const DecompositionSet& set) {
  RecordedDecomposition out;
  out.set = set;
  std::vector<DecompositionTest> tests;
  for (const auto& recorded : set.tests) tests.push_back(alignedTest(setup, set, recorded, out.alignment.emplace_back()));
  try {
    out.tests = decomposeErrors(tests, {set.referenceTest, set.degree});
  } catch (const std::invalid_argument& e) {
    throw InputError({set.file, set.tests[static_cast<size_t>(set.referenceTest)].line, fmt::format("tests[{}]", set.referenceTest)}, e.what());
  }
  std::array<std::vector<double>, 3> rms;
  std::vector<double> feeds;
  for (const auto& test : out.tests) {
    out.shares.push_back(decompositionShares(test));
    out.contouring.push_back(directionStatistics(test.contouring));
    std::vector<Vec3> quasiStatic(test.link.size());
    for (size_t i = 0; i < quasiStatic.size(); ++i) quasiStatic[i] = test.quasiStatic(i);
    out.quasiStatic.push_back(directionStatistics(quasiStatic));
    out.dynamic.push_back(directionStatistics(test.dynamic));
    feeds.push_back(test.feed);
    for (int d = 0; d < 3; ++d) rms[static_cast<size_t>(d)].push_back(out.dynamic.back().rms[d]);
  }
  for (size_t d = 0; d < 3; ++d) {
    try {
      out.dynamicLaw[d] = fitPowerLaw(feeds, rms[d]);
    } catch (const std::invalid_argument&) {
      out.dynamicLaw[d].reset();  // fewer than two feeds or an RMS of zero: no law to state
    }
  }
  return out;
}

nlohmann::json toJson(const RecordedDecomposition& r) {
  const auto um = [](const Vec3& v) { return nlohmann::json::array({v.x() * 1e3, v.y() * 1e3, v.z() * 1e3}); };
  nlohmann::json j;
  j["reference_feed_mm_min"] = r.tests[static_cast<size_t>(r.set.referenceTest)].feed;
  j["degree"] = r.set.degree;
  j["interpolation"] = r.set.interpolation == Interpolation::CubicSpline ? "cubic" : "linear";
  j["tests"] = nlohmann::json::array();
  for (size_t k = 0; k < r.tests.size(); ++k) {
    const auto& a = r.alignment[k];
    const auto& s = r.shares[k];
    j["tests"].push_back({
        {"feed_mm_min", r.tests[k].feed},
        {"clock_offset_ms", a.offset * 1e3},
        {"clock_offset_estimated", a.estimated},
        {"alignment_rms_misfit", a.rmsMisfit},
        {"instrument_samples", a.instrumentSamples},
        {"samples_used", a.samplesUsed},
        {"drift_um", um(r.tests[k].drift)},
        {"shares_percent",
         {{"contouring", s.contouring}, {"quasi_static", s.quasiStatic}, {"dynamic", s.dynamic}}},
        {"split_shares_percent",
         {{"contouring", s.splitContouring}, {"link", s.link}, {"motion", s.motion}, {"drift", s.drift}, {"dynamic", s.splitDynamic},
          {"over_printed_denominator", s.splitOverPrinted}}},
        {"contouring_max_um", um(r.contouring[k].maximum)},
        {"quasi_static_max_um", um(r.quasiStatic[k].maximum)},
        {"dynamic_max_um", um(r.dynamic[k].maximum)},
        {"dynamic_rms_um", um(r.dynamic[k].rms)},
    });
  }
  j["dynamic_rms_power_law"] = nlohmann::json::object();
  for (size_t d = 0; d < 3; ++d)
    if (const auto& law = r.dynamicLaw[d])
      j["dynamic_rms_power_law"][std::string(1, "xyz"[d])] = {
          {"kappa_um", law->kappa * 1e3}, {"exponent", law->exponent}, {"largest_relative_misfit", law->largestRelativeMisfit}};
  return j;
}

}  // namespace mtacc
