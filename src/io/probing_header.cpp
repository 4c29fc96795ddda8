#include "mtacc/io/probing_header.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/pose_text.hpp"

namespace mtacc {
namespace {

std::vector<double> numbers(const std::string& text, size_t count, const std::string& key) {
  const auto parts = splitFields(text);
  if (parts.size() != count) throw InputError(InputLocation{"", 0, key}, fmt::format("expected {} comma-separated numbers", count));
  std::vector<double> out;
  for (const auto& p : parts) out.push_back(parseNumber(p, key));
  return out;
}

}  // namespace

bool readProbingKey(const Machine& machine, const std::string& key, const std::string& value, int line, ProbingHeader& h) {
  const auto fail = [&](const std::string& what) { throw InputError(InputLocation{"", 0, key}, what); };
  if (key == "origin") {
    h.origin = parseLengths(value, key);
    h.originGiven = true;
    h.originLine = line;
  } else if (key == "axes") {
    const auto slash = value.find('/');
    if (slash == std::string::npos) fail("expected 'ux,uy,uz / vx,vy,vz'");
    const Vec3 u = parseVector(trim(value.substr(0, slash)), key), v = parseVector(trim(value.substr(slash + 1)), key);
    if (std::abs(u.norm() - 1) > 1e-6 || std::abs(v.norm() - 1) > 1e-6 || std::abs(u.dot(v)) > 1e-6)
      fail("the axes must be orthogonal unit vectors");
    h.u = u;
    h.v = v;
  } else if (key == "stylus") {
    h.stylus = parseLengths(value, key);
  } else if (key == "pose") {
    h.pose = parsePose(machine, value, key, true);
  } else if (key == "temperatures") {
    const auto t = numbers(value.substr(0, value.find_last_not_of(" C") + 1), 3, key);
    for (const double v : t)
      if (!(v > -50 && v < 100)) fail("temperatures in deg C");
    h.temperatures.scale = t[0];
    h.temperatures.plate = t[1];
    h.temperatures.reference = t[2];
  } else if (key == "expansion") {
    const auto e = numbers(value, 2, key);
    for (const double v : e)
      if (!(std::abs(v) < 1e-3)) fail("expansion coefficients in 1/K (e.g. 11.5e-6)");
    h.temperatures.scaleExpansion = e[0];
    h.temperatures.plateExpansion = e[1];
  } else if (key == "probe") {
    const size_t count = splitFields(value).size();
    if (count < 1 || count > 3) fail("expected 2S per probed direction, e.g. '1.1, 0.8 um'");
    h.probe = parseLengthList(value, count, key, "'2S, ... um'", "0.8, 0.9 um");
    for (const double s : h.probe)
      if (!(s > 0.0 && s < 1.0)) fail("probe 2S from above 0 to 1 mm");
  } else if (key == "simulation") {
    h.simulation = parseQuantityAs(value, Dimension::Length, key);
    if (!(*h.simulation >= 0.0 && *h.simulation < 1.0)) fail("a 2S from 0 to 1 mm");
  } else {
    return false;
  }
  return true;
}

std::string probingHeaderText(const Machine& machine, const ProbingHeader& h) {
  std::string out = fmt::format("# origin: {}, {}, {} mm\n# axes: {},{},{} / {},{},{}\n", h.origin.x(), h.origin.y(), h.origin.z(), h.u.x(),
                                h.u.y(), h.u.z(), h.v.x(), h.v.y(), h.v.z());
  out += fmt::format("# stylus: {}, {}, {} mm\n", h.stylus.x(), h.stylus.y(), h.stylus.z());
  std::string pose;
  for (int a = 0; a < machine.commandedCount(); ++a)
    if (machine.axes[static_cast<size_t>(a)].isRotary() && !h.pose.empty())
      pose += fmt::format("{}{}={}", pose.empty() ? "" : ",", machine.axes[static_cast<size_t>(a)].name, h.pose[static_cast<size_t>(a)] / kDeg);
  if (!pose.empty()) out += "# pose: " + pose + "\n";
  const auto& t = h.temperatures;
  out += fmt::format("# temperatures: {}, {}, {} C\n# expansion: {}, {}\n", t.scale, t.plate, t.reference, t.scaleExpansion, t.plateExpansion);
  if (!h.probe.empty()) {
    std::string probe;
    for (const double s : h.probe) probe += fmt::format("{}{:.10g}", probe.empty() ? "" : ", ", s * 1e3);
    out += "# probe: " + probe + " um\n";
  }
  if (h.simulation) out += fmt::format("# simulation: {:.10g} um\n", *h.simulation * 1e3);
  return out;
}

}  // namespace mtacc
