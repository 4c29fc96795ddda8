#pragma once
// The runs a measurement design chooses from, generated within the machine's travel for the
// instruments at hand: R-test and touch-probe sphere runs over each rotary axis (the sphere at
// the tool's reach from the line and along it, the other rotary axes at several positions, a few
// numbers of positions per sweep), the ballbar's radial, tangential and axial tests of each rotary
// axis and ISO 230-4 ballbar circles in the three planes, at each bar length. Each carries the plan entry that
// regenerates it and the set-up unknowns an identification estimates with it.
#include <string>
#include <vector>

#include "mtacc/measurement/measurement.hpp"

namespace mtacc {

struct CandidateOptions {
  std::vector<Instrument> instruments{Instrument::RTest, Instrument::Ballbar};
  std::vector<double> radii{50.0, 100.0, 200.0};  // mm: the sphere (work ball) from a table axis's line
  double spread = 100.0;         // mm: the second sphere along the line, or the tool ball beyond the tip on a head axis
  std::vector<double> ballbarLengths{100.0, 150.0};  // mm
  std::vector<int> positions{8, 16};  // R-test and probe positions per sweep
  int ballbarPoints = 72;        // ballbar readings per sweep (a circle: per direction)
  double feed = 1000.0;          // mm/min: the ballbar's contouring feed
};

struct DesignCandidate {
  std::string name;
  std::string description;
  std::string planEntry;  // the plan YAML run (docs/file-formats.md "Test plans"), with its estimate
  MeasurementRun run;     // nominal poses, `estimate` set
};

struct CandidateSet {
  std::vector<DesignCandidate> candidates;
  std::vector<std::string> notes;  // families not generated, and why
};

// Throws InvalidInput when no candidate can be generated for the instruments (e.g. sphere runs on
// a machine without a rotary axis and no ballbar).
CandidateSet designCandidates(const KinematicModel& nominal, const CandidateOptions& options);

}  // namespace mtacc
