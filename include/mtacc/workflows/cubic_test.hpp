#pragma once
// Workflow `cubic`: seed 001's cubic machining test on a machine — the tool path and NC
// program, the machined surface simulated by material removal from the erroneous path, the
// zones evaluated as the seed measures them, and the sensitivity of every zone to each error
// with and without the workpiece-to-table transformation M_WC.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/procedures/scanned_surface.hpp"
#include "mtacc/procedures/zone_planes.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct CubicTestRequest {
  CubicTestSpec spec = seed001CubicTest();
  double gridSpacing = 0.01;     // mm, over the whole block
  double chordTolerance = 1e-6;  // mm, of the actual path against its chords
  double inset = 1.0;            // mm left out along each zone edge when zones are evaluated
  // Sensitivities k = E / epsilon (seed 001 eq. 15) of each named error (default: every
  // location error of the rotary axes), each alone at epsilon, both alignments.
  bool sensitivities = false;
  std::vector<std::string> sensitivityParameters;
  // mm; five cells per 0.1 mm pick, so that the scallops, shifted by epsilon, change a zone
  // mean by about 0.01 um (0.001 mm/mm at epsilon = 10 um); two per pick would give 0.07 um.
  double sensitivityGrid = 0.02;
  double lengthStep = 0.01, angleStep = 0.01 * kDeg;  // epsilon: 10 um, 0.01 deg
  int threads = kAllCores;
  std::function<void(const std::string&)> progress;  // one line per stage
  // A scanned face of the machined block (docs/file-formats.md "Scanned surfaces"), evaluated
  // beside the simulation on a grid of `scanGrid` mm; empty: none.
  std::string scanFile;
  double scanGrid = 0.5;
  // The axes' actual positions recorded during the cut (docs/file-formats.md "Recorded axis
  // positions"), machined beside the programmed path (seed 001 Eqs 13-14); empty: none.
  std::string traceFile;
};

struct CubicZoneResult {
  std::string name;
  std::vector<double> clamped;  // commanded axes while the zone is cut (mm, rad)
  ZonePlane deviation;          // E = machined - error-free surface (seed 001 L193), workpiece frame
  ZonePlane measured;           // the machined surface referenced to the reference zone (L239)
};

// Sensitivity of each zone to one error: E / epsilon of the zone planes.
struct CubicSensitivity {
  std::string name;            // as requested
  Dimension dimension;
  double step = 0;             // epsilon (mm or rad)
  std::vector<ZonePlane> withAlignment, onTable;  // per zone, per unit error (mm/mm or mm/rad)
  HeightMap mapWithAlignment, mapOnTable;          // E / epsilon over the block, sensitivity grid
};

// A scanned face: its points, the height map they give and the zone planes referenced to the
// reference zone (seed 001 L239), as the simulated surface's `measured`.
struct ScannedCubicTest {
  size_t points = 0;
  HeightMap map;
  std::vector<ZonePlane> zones;
};

// The zones of a scanned face (`points`, workpiece frame) on a grid of `gridSpacing` mm; throws
// InputError naming `file` when a zone has fewer than three cells with a height.
ScannedCubicTest scannedCubicTest(const std::vector<Vec3>& points, const CubicTestSpec& spec, double gridSpacing, double inset,
                                  size_t referenceZone, const std::string& file);

// The surface machined along recorded axis positions: the cutting runs found in the trace, the
// surface and its zone planes referenced to the reference zone.
struct TracedCubicTest {
  size_t samples = 0, cuttingSamples = 0;
  std::vector<CubicZonePath> runs;
  std::vector<std::vector<ToolPoint>> cl;  // per run and sample: the tool tip and vector through the machine with its errors (Eq. 13)
  HeightMap map;
  std::vector<ZonePlane> zones;
};
// The recorded positions of the machine's commanded axes in `path` (mm, rad per row).
JointMatrix readAxisTrace(const Machine& machine, const std::string& path);
// The CL data of Eqs 13-14: per run and sample the tool tip (x, y, z mm) and vector (i, j, k), CSV.
std::string traceClCsv(const TracedCubicTest& trace);

struct CubicTestStudy {
  std::shared_ptr<const Machine> machine;
  CubicTestRequest options;
  std::vector<CubicZonePath> path;
  size_t referenceZone = 0;
  size_t cutterMoves = 0;      // straight moves of the actual path after chord refinement
  HeightMap nominal, actual;   // machined surfaces without and with the machine's errors
  std::vector<CubicZoneResult> zones;
  std::vector<CubicSensitivity> sensitivities;
  std::optional<ScannedCubicTest> scan;
  std::optional<TracedCubicTest> trace;
};

// The options of `cubic`, declared once: the study's (read by cubicTestRequest) and the files to
// write (test_piece_files.hpp: cubicTestFiles). Lengths in mm.
const OptionSchema& cubicTestSchema();
CubicTestRequest cubicTestRequest(const OptionValues& values);

// Throws InputError for a spec or option out of range and for a zone the machine cannot reach.
CubicTestStudy cubicTestStudy(const MachineSetup& setup, const CubicTestRequest& options);
nlohmann::json toJson(const CubicTestStudy& study);
// The deviation E (machined minus error-free surface) less the reference zone's plane of it:
// the simulated counterpart of the measured map of seed 001 Fig. 16.
HeightMap referencedDeviation(const CubicTestStudy& study);

}  // namespace mtacc
