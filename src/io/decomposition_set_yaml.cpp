#include "mtacc/io/decomposition_set_yaml.hpp"

#include <filesystem>

#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {

namespace {

double positiveRate(const yamlin::Context& ctx, const YAML::Node& node, const std::string& key) {
  const double hz = yamlin::number(ctx, node, key);
  if (!(hz >= 1.0 && hz <= 1e7)) ctx.fail(node, key, "a rate in [1, 1e7] Hz");
  return 1.0 / hz;
}

std::string besideTheSet(const std::string& setFile, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute() || setFile.empty()) return path;
  return (std::filesystem::path(setFile).parent_path() / p).string();
}

}  // namespace

DriftFrame parseDriftFrame(const std::string& text, const InputLocation& key) {
  if (text == "machine") return DriftFrame::Machine;
  if (text == "workpiece") return DriftFrame::Workpiece;
  throw InputError(key, "expected machine (seed 004's: constant in the machine frame) or workpiece, not '" + text + "'");
}

DecompositionSet parseDecompositionSet(const std::string& text, const std::string& source) {
  const yamlin::Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping with tests: [{feed, command, encoder, instrument}, ...]");
  yamlin::rejectUnknownKeys(ctx, root, "",
                            {"description", "ball", "nc_rate_hz", "instrument_rate_hz", "interpolation", "clock_offset_ms", "largest_lag_ms", "search_ms",
                             "reference_feed", "degree", "parameter", "drift_frame", "reference_fit", "tests"});
  DecompositionSet set;
  set.file = source;
  if (root["ball"]) set.ball = yamlin::lengthVector(ctx, root["ball"], "ball");
  if (root["nc_rate_hz"]) set.ncPeriod = positiveRate(ctx, root["nc_rate_hz"], "nc_rate_hz");
  if (root["instrument_rate_hz"]) set.instrumentPeriod = positiveRate(ctx, root["instrument_rate_hz"], "instrument_rate_hz");
  if (const auto node = root["interpolation"]) {
    const auto kind = yamlin::scalar(ctx, node, "interpolation");
    if (kind != "cubic" && kind != "linear") ctx.fail(node, "interpolation", "expected cubic or linear (the paper's)");
    set.interpolation = kind == "cubic" ? Interpolation::CubicSpline : Interpolation::Linear;
  }
  if (const auto node = root["clock_offset_ms"]) {
    const double ms = yamlin::number(ctx, node, "clock_offset_ms");
    if (!(std::abs(ms) <= 1e4)) ctx.fail(node, "clock_offset_ms", "must lie within +-10000 ms");
    set.clockOffset = ms * 1e-3;
  }
  if (const auto node = root["largest_lag_ms"]) {
    const double ms = yamlin::number(ctx, node, "largest_lag_ms");
    if (!(ms >= 0.0 && ms <= 1e4)) ctx.fail(node, "largest_lag_ms", "must lie within 0 to 10000 ms");
    set.largestLag = ms * 1e-3;
  }
  if (const auto node = root["search_ms"]) {
    if (!yamlin::isSequence(node) || node.size() != 2) ctx.fail(node, "search_ms", "expected [lowest, highest] in ms");
    const double lo = yamlin::number(ctx, node[0], "search_ms"), hi = yamlin::number(ctx, node[1], "search_ms");
    if (!(lo < hi && lo >= -1e4 && hi <= 1e4)) ctx.fail(node, "search_ms", "expected lowest < highest within +-10000 ms");
    set.searchLowest = lo * 1e-3;
    set.searchHighest = hi * 1e-3;
  }
  if (root["degree"]) set.degree = yamlin::wholeNumber(ctx, root["degree"], "degree", 0, 60);
  if (const auto node = root["parameter"]) {
    const auto kind = yamlin::scalar(ctx, node, "parameter");
    if (kind != "path" && kind != "time") ctx.fail(node, "parameter", "expected path or time (the paper's)");
    set.parameter = kind == "path" ? MotionParameter::Path : MotionParameter::Time;
  }
  if (const auto node = root["reference_fit"]) {
    const auto kind = yamlin::scalar(ctx, node, "reference_fit");
    if (kind != "steady" && kind != "all")
      ctx.fail(node, "reference_fit", "expected steady (the reference's samples where its axes accelerate left out of the motion-error fit) or all (the paper's)");
    set.referenceFit = kind == "steady" ? ReferenceFit::Steady : ReferenceFit::All;
  }
  if (const auto node = root["drift_frame"])
    set.driftFrame = parseDriftFrame(yamlin::scalar(ctx, node, "drift_frame"), ctx.at(node, "drift_frame"));

  const auto tests = root["tests"];
  if (!yamlin::isSequence(tests) || tests.size() == 0)
    ctx.fail(tests ? tests : root, "tests", "expected a list of {feed, command, encoder, instrument}");
  if (tests.size() > 100) ctx.fail(tests, "tests", "at most 100 tests");
  for (size_t k = 0; k < tests.size(); ++k) {
    const auto t = tests[k];
    const std::string key = "tests[" + std::to_string(k) + "]";
    if (!yamlin::isMap(t)) ctx.fail(t, key, "expected {feed, command, encoder, instrument}");
    yamlin::rejectUnknownKeys(ctx, t, key, {"feed", "command", "encoder", "instrument"});
    RecordedTest test;
    test.line = static_cast<int>(t.Mark().line) + 1;
    if (!t["feed"]) ctx.fail(t, key + ".feed", "missing (mm/min as programmed)");
    test.feed = yamlin::number(ctx, t["feed"], key + ".feed");
    if (!(test.feed > 0 && test.feed <= 1e6)) ctx.fail(t["feed"], key + ".feed", "a feed in (0, 1e6] mm/min");
    for (const auto& [name, into] : {std::pair{"command", &test.command}, {"encoder", &test.encoder}, {"instrument", &test.instrument}}) {
      if (!t[name]) ctx.fail(t, key + "." + name, "missing (a signal CSV file)");
      *into = besideTheSet(source, yamlin::scalar(ctx, t[name], key + "." + name));
      if (!std::filesystem::is_regular_file(*into)) ctx.fail(t[name], key + "." + name, *into + ": no such file");
    }
    for (const auto& other : set.tests)
      if (other.feed == test.feed) ctx.fail(t["feed"], key + ".feed", "a second test at the same feed");
    set.tests.push_back(test);
  }
  size_t reference = 0;
  for (size_t k = 1; k < set.tests.size(); ++k)
    if (set.tests[k].feed < set.tests[reference].feed) reference = k;
  if (const auto node = root["reference_feed"]) {
    const double feed = yamlin::number(ctx, node, "reference_feed");
    reference = set.tests.size();
    for (size_t k = 0; k < set.tests.size(); ++k)
      if (set.tests[k].feed == feed) reference = k;
    if (reference == set.tests.size()) ctx.fail(node, "reference_feed", "no test at this feed");
  }
  set.referenceTest = static_cast<int>(reference);
  return set;
}

DecompositionSet loadDecompositionSet(const std::string& path) {
  return parseDecompositionSet(readTextFile(path), path);
}

}  // namespace mtacc
