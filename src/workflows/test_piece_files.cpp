#include "mtacc/workflows/test_piece_files.hpp"

#include <fmt/format.h>

#include <initializer_list>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text_file.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/io/cone_program.hpp"
#include "mtacc/io/cubic_program.hpp"
#include "mtacc/io/surface_files.hpp"
#include "mtacc/io/zone_results_csv.hpp"
#include "mtacc/workflows/cubic_identification.hpp"

namespace mtacc {
namespace {

// The file's format from its extension, one of `allowed`; InputError at `key` otherwise.
std::string formatOf(const std::string& path, const std::string& key, std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* ext : allowed) {
    if (path.ends_with(std::string(".") + ext)) return ext;
    list += std::string(list.empty() ? "" : ", ") + "." + ext;
  }
  throw InputError(InputLocation{"", 0, key}, "'" + path + "': expected a file ending in " + list);
}

// The deviation shown at full colour, mm.
double mapLimitOf(const CubicTestFiles& files) {
  const double limit = parseQuantityAs(files.mapLimit, Dimension::Length, "map_limit");
  if (!(limit >= 1e-6 && limit <= 10)) throw InputError(InputLocation{"", 0, "map_limit"}, "must be from 1 nm to 10 mm");
  return limit;
}

// Writes `content` to `path` and says so in `written`.
void writeAndNote(std::vector<std::string>& written, const std::string& path, const std::string& content, const std::string& key,
                  const std::string& what) {
  writeFileAtomically(path, content, key);
  written.push_back(what + " written: " + path);
}

}  // namespace

std::vector<std::string> writeConeFiles(const ConeStudy& s, const ConeFiles& files) {
  std::vector<std::string> written;
  if (!files.cl.empty()) writeAndNote(written, files.cl, coneClData(s.path), "cl", "CL data");
  if (!files.gcode.empty()) writeAndNote(written, files.gcode, coneNcProgram(*s.machine, s.options.spec, s.motion.q, s.options.feed), "gcode", "NC program");
  return written;
}

ConeFiles coneFiles(const OptionValues& values) {
  const OptionReader read(coneSchema(), values);
  return {read.text("gcode").value_or(""), read.text("cl").value_or("")};
}

void checkCubicTestFiles(const CubicTestFiles& files) {
  if (!files.map.empty()) formatOf(files.map, "map", {"svg", "png"});
  if (!files.heights.empty()) formatOf(files.heights, "heights", {"csv", "npy"});
  if (!files.surface.empty()) formatOf(files.surface, "surface", {"ply", "stl"});
  mapLimitOf(files);
}

CubicTestFiles cubicTestFiles(const OptionValues& values) {
  const OptionReader read(cubicTestSchema(), values);
  CubicTestFiles f;
  for (auto [key, field] : {std::pair{"gcode", &f.gcode}, {"cl", &f.cl}, {"map", &f.map}, {"map_limit", &f.mapLimit}, {"heights", &f.heights},
                            {"surface", &f.surface}, {"zones_out", &f.zonesOut}, {"scan_zones_out", &f.scanZonesOut}, {"trace_cl", &f.traceCl}})
    *field = read.text(key).value_or("");
  if (!f.scanZonesOut.empty() && !read.text("scan")) throw InputError(InputLocation{"", 0, "scan_zones_out"}, "give the scan (--scan) whose zones to write");
  if (!f.traceCl.empty() && !read.text("trace")) throw InputError(InputLocation{"", 0, "trace_cl"}, "give the trace (--trace) whose CL data to write");
  return f;
}

std::vector<std::string> writeCubicTestFiles(const CubicTestStudy& s, const CubicTestFiles& files) {
  checkCubicTestFiles(files);
  const Machine& m = *s.machine;
  const CubicTestSpec& spec = s.options.spec;
  std::vector<std::string> written;
  if (!files.gcode.empty()) writeAndNote(written, files.gcode, cubicNcProgram(m, spec, s.path), "gcode", "NC program");
  if (!files.cl.empty()) writeAndNote(written, files.cl, cubicClData(spec, s.path), "cl", "CL data");
  if (!files.map.empty()) {
    const auto referenced = referencedDeviation(s);
    const ColourMap colours{mapLimitOf(files), 1200};
    std::vector<ZonePlane> measured;
    for (const auto& z : s.zones) measured.push_back(z.measured);
    const std::string title = fmt::format("{}: machined minus error-free surface, referenced to zone {}", m.name, spec.zones[s.referenceZone].name);
    writeAndNote(written, files.map, formatOf(files.map, "map", {"svg", "png"}) == "png" ? heightMapPng(referenced, colours)
                                                                         : zoneMapSvg(referenced, colours, spec, measured, title),
          "map", "surface map");
  }
  if (!files.heights.empty())
    writeAndNote(written, files.heights, formatOf(files.heights, "heights", {"csv", "npy"}) == "csv" ? heightMapCsv(s.actual) : heightMapNpy(s.actual),
          "heights", "heights");
  if (!files.surface.empty()) {
    const int stride = exportStride(s.actual.grid);
    writeAndNote(written, files.surface, formatOf(files.surface, "surface", {"ply", "stl"}) == "ply" ? heightMapPly(s.actual, stride) : heightMapStl(s.actual, stride),
          "surface", fmt::format("surface (every {} cell{})", stride, stride > 1 ? "s" : ""));
  }
  std::vector<ZonePlane> simulated;
  for (const auto& z : s.zones) simulated.push_back(z.measured);
  if (!files.zonesOut.empty())
    writeAndNote(written, files.zonesOut, zoneResultsCsv(zoneResults(s.options.spec, simulated)), "zones_out", "zone results");
  if (!files.traceCl.empty() && s.trace)
    writeAndNote(written, files.traceCl, traceClCsv(*s.trace), "trace_cl", "CL data of the recorded positions");
  if (!files.scanZonesOut.empty() && s.scan) {
    writeAndNote(written, files.scanZonesOut, zoneResultsCsv(zoneResults(s.options.spec, s.scan->zones)), "scan_zones_out",
                 "scanned zone results");
  }
  return written;
}

}  // namespace mtacc
