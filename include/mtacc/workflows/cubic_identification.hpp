#pragma once
// Workflow `cubic-identify`: the machine's errors from the zone results of a cubic machining
// test (seed 001 §7.3): what the zones' heights (and tilts) determine, estimated with standard
// uncertainties, and a refusal naming what they cannot separate. The readings are referenced
// to the reference zone as the seed measures them, which to first order is the workpiece
// aligned with the machine (M_WC, eqs. 10-12; extraction §6.3): the model uses that alignment.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/io/zone_results_csv.hpp"
#include "mtacc/workflows/cubic_test.hpp"
#include "mtacc/workflows/identification.hpp"

namespace mtacc {

struct CubicIdentificationRequest {
  std::string test = "seed001-cubic";  // the test piece (file or bundled name)
  std::string zonesFile;               // zone results (io/zone_results_csv.hpp)
  std::vector<std::string> parameters;
  std::optional<double> noise;         // mm; default: the file's '# noise:' line
  int threads = kAllCores;
};

// The options of `cubic-identify`, declared once, and the request they describe (zones and
// parameters must be given); throws InputError naming the key.
const OptionSchema& cubicIdentificationSchema();
CubicIdentificationRequest cubicIdentificationRequest(const OptionValues& values);

IdentificationStudy identifyFromZones(const MachineSetup& setup, const CubicIdentificationRequest& request);
// The same from zone results in memory (the file's name in results.file, for messages).
IdentificationStudy identifyFromZones(const MachineSetup& setup, const CubicTestSpec& spec, const ZoneResults& results,
                                        const CubicIdentificationRequest& request);

// Zone planes referenced to the reference zone as zone results (heights with their tilts): a
// study's simulated `measured` planes, or a scan's.
ZoneResults zoneResults(const CubicTestSpec& spec, const std::vector<ZonePlane>& referenced);

}  // namespace mtacc
