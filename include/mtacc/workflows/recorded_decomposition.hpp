#pragma once
// Seed 004 on recorded signals: per test of a decomposition set, the command trace moved onto
// the encoder clock (the offset given or estimated), both traces resampled at the instrument's
// samples, the machine's nominal direct kinematics for chi_nom and chi_enc, the link errors of
// the errors file along the encoder path, then the decomposition of eqs. 6, 10-20 and its
// statistics (eqs. 21-23) over the feeds.
#include <array>
#include <optional>

#include <nlohmann/json.hpp>

#include "mtacc/core/option_schema.hpp"
#include "mtacc/io/decomposition_set_yaml.hpp"
#include "mtacc/procedures/recorded_test.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

struct RecordedDecomposition {
  DecompositionSet set;
  std::vector<TestAlignment> alignment;   // per test, in the set's order
  std::vector<DecomposedTest> tests;
  std::vector<LargeVector<double>> pathFraction;  // per test and sample: u, the encoder path travelled over its whole (Figs 9-10's abscissa)
  std::vector<DecompositionShares> shares;
  std::vector<DirectionStatistics> contouring, quasiStatic, dynamic;
  std::vector<DirectionStatistics> contouringOrthogonal;  // Fig. 4's, over the samples where the path has a tangent
  // With an identified errors file: the standard uncertainty (k = 1) of delta_l per test (its
  // maximum and RMS along the path, per direction), propagated from the record's covariance of
  // the parameters named in `linkParameters`; empty without a record.
  std::vector<DirectionStatistics> linkUncertainty;
  std::vector<std::string> linkParameters, linkLeftOut;
  // delta_d RMS against feed per direction (eq. 23); absent for fewer than two feeds or a zero RMS
  std::array<std::optional<PowerLaw>, 3> dynamicLaw;
  // What makes a result doubtful: a clock offset estimated at its search limit, spikes in an
  // instrument signal. One sentence each; `decompose --strict` exits non-zero on any.
  std::vector<std::string> warnings;
};

// set (the decomposition set's file), series (points of each test's contributions along u in the
// JSON, 0: none), drift_frame ("machine" or "workpiece"; as the set says when not given).
struct DecompositionRequest {
  std::string set;
  std::optional<std::string> driftFrame;
  size_t seriesPoints = 0;
};
const OptionSchema& decompositionSchema();
DecompositionRequest decompositionRequest(const OptionValues& values);

// The request's set with its drift frame replaced, which is checked before the set's files are
// read (an error names drift_frame).
DecompositionSet loadDecompositionSet(const DecompositionRequest& request);

// The errors file's model is taken as the identified link errors (delta_l = its TCP minus the
// nominal TCP at the encoder positions); without one, delta_l = 0 and the reference test's fit
// holds all the quasi-static error. With the covariance of an identified errors file (setup's),
// delta_l's uncertainty along each test. Throws InputError naming the set or signal file.
RecordedDecomposition decomposeRecordedSet(const MachineSetup& setup, const DecompositionSet& set);
// Lengths in um, offsets in ms, shares in %. With seriesPoints > 0, each test also holds its
// contributions along u ("series"): every k-th sample, k chosen for at most seriesPoints.
nlohmann::json toJson(const RecordedDecomposition& result, size_t seriesPoints = 0);

}  // namespace mtacc
