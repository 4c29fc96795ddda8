#pragma once
// From the direct-measurement runs of one component error to its fitted error function (seed 003
// ch. 4.2 and 5.2): read the runs, apply the corrections the file asks for (scale temperature,
// Abbe offset with the axis's rotation errors from the machine's error model), flag disturbed
// readings, average forward and backward over the runs, fit the C1 piecewise polynomial with
// stepwise removal (and a periodic term), and put it in the machine's error model.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "mtacc/io/component_runs_csv.hpp"
#include "mtacc/core/option_schema.hpp"
#include "mtacc/measurement/component_fit.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct ComponentFitRequest {
  std::string file = "";
  // Positions in the axis's unit at the interfaces: mm, or deg for a rotary axis.
  std::vector<double> breaks;  // increasing, within the travel, covering the data; empty: `pieces`
  int pieces = 0;              // equal intervals over the measured range; 0 with no breaks: about 100 mm (30 deg) each
  int degree = 2;
  double significance = 0.05;  // of the stepwise removal; 0 keeps every term
  std::optional<double> period = std::nullopt;  // mm or deg
  double periodZero = 0.0;                      // mm or deg
  double disturbanceThreshold = 5.0;  // robust standard deviations
  bool removeDisturbed = false;       // leave the flagged readings and unsettled runs out of the means
};

// The options of `fit`, declared once (positions in the axis unit, mm or deg), and the request
// they describe; throws InputError naming the key.
const OptionSchema& componentFitSchema();
ComponentFitRequest componentFitRequest(const OptionValues& values);

struct ComponentFitStudy {
  std::shared_ptr<const Machine> machine;
  ComponentRunsFile data;  // the runs after the corrections
  std::vector<std::string> corrections;
  ComponentCurve curve;
  Disturbances disturbances;
  ComponentFit fit;
  ErrorModel errors;  // the machine's errors (as given) with the fitted function in place of the component's
  std::string yaml;   // the `errors:` entry of the fitted function
};

// Throws InputError naming the file (its line and key) or the request's key ("breaks", "pieces",
// "period", "degree", "significance").
ComponentFitStudy fitComponentFile(const MachineSetup& setup, const ComponentFitRequest& request);

// Positions in mm or deg, errors in um or urad (the runs, means, the fit and its standard
// uncertainty at the positions and on a fine grid), the terms, removed terms, flags, the YAML.
nlohmann::json toJson(const ComponentFitStudy& study);

// Direct-measurement runs of one component simulated on a machine with its errors (the truth
// the fit should recover), written atomically to `output` in the component-runs format.
struct ComponentSimulationRequest {
  std::string component = "";  // seed 003 or ISO name: xrx, EAX, ...
  std::string output = "";
  double step = 10.0;          // mm or deg, over the axis travel (one turn for a continuous axis)
  int runs = 20;
  std::string noise = "";  // one reading's standard deviation, a length or an angle as the component; empty: none
  Vec3 abbeOffset = Vec3::Zero();  // mm, translations only
  std::string instrument = "";
  double readingTime = 6.0;    // s per reading
  std::string disturbance = "";  // e.g. "1.5 arcsec": one reading that high every `disturbanceInterval`
  double disturbanceInterval = 1800.0;  // s
  std::string settling = "";      // e.g. "2 arcsec": a drift of that size at the start, decaying
  double settlingTime = 600.0;    // s: its time constant
  std::uint64_t seed = 1;
};
ComponentRunsFile simulateComponentFile(const MachineSetup& setup, const ComponentSimulationRequest& request);
// The options of `simulate component`, by the request's fields' names; the values are checked
// where the runs are simulated.
const OptionSchema& componentSimulationSchema();
ComponentSimulationRequest componentSimulationRequest(const OptionValues& values);

}  // namespace mtacc
