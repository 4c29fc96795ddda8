#include "mtacc/workflows/cubic_identification.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/cubic_test_yaml.hpp"

namespace mtacc {

IdentificationStudy identifyFromZones(const MachineSetup& setup, const CubicTestSpec& spec, const ZoneResults& results,
                                        const CubicIdentificationRequest& request) {
  auto machine = std::make_shared<Machine>(*setup.machine);
  machine->alignment = WorkpieceAlignment::Machine;
  const MachineSetup aligned{machine, setup.errors, setup.covariance};
  const bool slopes = std::all_of(results.zones.begin(), results.zones.end(), [](const auto& z) { return z.slopeX.has_value(); });
  std::vector<MeasurementRun> all;
  try {
    all = cubicZoneRuns(aligned.nominal(), spec, slopes);
  } catch (const UnreachablePose& e) {
    throw UnreachableInput(InputLocation{"", 0, "test"}, std::string("the test cannot be machined: ") + e.what());
  }
  const auto points = cubicZoneRunPoints(spec, slopes);
  IdentificationRequest r;
  r.parameters = request.parameters;
  r.noise = request.noise;
  r.threads = request.threads;
  for (const auto& z : results.zones) {
    const auto at = std::find_if(spec.zones.begin(), spec.zones.end(), [&](const auto& s) { return s.name == z.name; });
    if (at == spec.zones.end()) throw InputError(InputLocation{results.file, z.line, "zone"}, "no zone '" + z.name + "' in the test");
    MeasurementRun run = all[static_cast<size_t>(at - spec.zones.begin())];
    run.readings.resize(static_cast<Eigen::Index>(points.size()), 1);
    for (size_t k = 0; k < points.size(); ++k)
      run.readings(static_cast<Eigen::Index>(k), 0) =
          z.height + (slopes ? *z.slopeX * points[k][0] + *z.slopeY * points[k][1] : 0.0);
    run.noise = results.noise;
    r.runs.push_back(std::move(run));
  }
  auto outcome = identifyParameters(aligned, r);
  // The zone model measures each zone at its clamped pose at standstill; the cut moves the axes,
  // and a reversal error shifts it by half its width one way or the other. Held at their values,
  // such errors are not in the model, and what they do to the cut biases the estimates.
  std::vector<std::string> reversals;
  for (size_t a = 0; a < setup.errors.axes.size(); ++a)
    for (int c = 0; c < 6; ++c)
      for (const auto& t : setup.errors.axes[a].motion[static_cast<size_t>(c)].terms())
        if (const auto* rev = std::get_if<ReversalTerm>(&t); rev && rev->width != 0.0)
          reversals.push_back(motionErrorName(*setup.machine, static_cast<int>(a), c));
  if (!reversals.empty())
    outcome.quality.warnings.push_back(
        fmt::format("the errors have reversal terms ({}): ", fmt::join(reversals, ", ")) +
        "the zone model takes each zone at its clamped pose at standstill and does not see what a reversal does to the "
        "cut, so the estimates carry their effect (simulate the zones without them, or measure them and compensate first)");
  return outcome;
}

const OptionSchema& cubicIdentificationSchema() {
  static const OptionSchema schema{
      "cubic-identify",
      {{"zones", OptionKind::Text, "Zone results: zone,height_um[,slope_x_um_per_mm,slope_y_um_per_mm] (CSV)"},
       {"parameters", OptionKind::List, "Parameters to determine, e.g. dxBY,alphaBY,alphaCB,betaBY (ISO names or aliases)"},
       {.key = "test", .kind = OptionKind::Text, .help = "Test piece (YAML) or bundled name", .defaultText = "seed001-cubic"},
       {.key = "noise", .kind = OptionKind::Quantity, .help = "Height noise (standard deviation); default: the file's '# noise:' line",
        .low = 1e-6, .high = 1.0, .outOfRange = "must be from 1 nm to 1 mm"},
       threadsOption()}};
  return schema;
}

CubicIdentificationRequest cubicIdentificationRequest(const OptionValues& values) {
  const OptionReader read(cubicIdentificationSchema(), values);
  CubicIdentificationRequest r;
  r.zonesFile = read.text("zones").value_or("");
  if (r.zonesFile.empty()) throw InputError(InputLocation{"", 0, "zones"}, "give the zone results of the test (CSV)");
  r.parameters = read.list("parameters");
  if (r.parameters.empty()) throw InputError(InputLocation{"", 0, "parameters"}, "name the parameters to determine, e.g. dxBY,alphaBY");
  r.test = *read.text("test");
  r.noise = read.quantity("noise");
  r.threads = *read.count("threads");
  return r;
}

IdentificationStudy identifyFromZones(const MachineSetup& setup, const CubicIdentificationRequest& request) {
  auto outcome = identifyFromZones(setup, loadCubicTest(request.test), readZoneResults(request.zonesFile), request);
  outcome.command = "cubic-identify";
  outcome.plan = request.test;
  outcome.dataFiles = {request.zonesFile};
  return outcome;
}

ZoneResults zoneResults(const CubicTestSpec& spec, const std::vector<ZonePlane>& referenced) {
  ZoneResults r;
  for (size_t k = 0; k < referenced.size(); ++k)
    r.zones.push_back({spec.zones[k].name, referenced[k].mean, referenced[k].slopeX, referenced[k].slopeY, 0});
  return r;
}

}  // namespace mtacc
