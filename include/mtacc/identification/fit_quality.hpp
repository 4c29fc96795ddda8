#pragma once
// What an identification's own numbers say about its trustworthiness: the goodness of fit
// against the stated reading noise, the parameters it hardly determines, the strongly
// correlated pairs, and a harmonic's amplitude and phase with their uncertainties.
#include <optional>
#include <string>
#include <vector>

#include "mtacc/identification/identification.hpp"

namespace mtacc {

// The plausible magnitude of a geometric or set-up error of a machine tool: about four times
// the largest location-error limits of seed 000 Table 3.9 (11.6 um and 50 urad,
// data/limits/seed000-table3.9.yaml).
constexpr double kPlausibleLength = 0.05;  // mm (50 um)
constexpr double kPlausibleAngle = 200e-6; // rad (200 urad)
// The goodness-of-fit test fails below this p-value.
constexpr double kFitSignificance = 0.01;

// What the identification's own numbers say about its trustworthiness.
struct IdentificationQuality {
  std::optional<double> chiSquare, pValue;  // against the stated noise; unset when none is stated
  std::string noiseSource;                  // where the noise was stated: set by the caller that read it ("--noise"); empty: none
  std::vector<size_t> poorlyDetermined;     // columns whose uncertainty exceeds the limit
  std::vector<std::string> warnings;        // one sentence each; empty when nothing is wrong
};

// The quality of `result`: the chi-square of its residuals against `statedNoise` (mm; unset:
// each run's own noise, no test when a run has none), and the parameters whose standard
// uncertainty exceeds `uncertaintyFraction` of their plausible magnitude.
IdentificationQuality fitQuality(const IdentificationResult& result, std::optional<double> statedNoise, double uncertaintyFraction);

// A harmonic identified as its cosine and sine parts (a plan's "ECC.h1"), as amplitude and
// phase: a cos(x) + b sin(x) = amplitude cos(x + phase), with their standard uncertainties
// from the covariance (first order; the phase's is meaningless when the amplitude is within
// its uncertainty of zero).
struct HarmonicEstimate {
  std::string name;  // "ECC.h1"
  Dimension dimension;
  double amplitude, amplitudeUncertainty;  // mm or rad
  double phase, phaseUncertainty;          // rad
};

// Every harmonic of `result` identified as its cosine and sine terms (names ending ".h<k>c" and ".h<k>s").
std::vector<HarmonicEstimate> harmonicEstimates(const IdentificationResult& result);

// "A and B: 0.953" for each pair among the first `count` unknowns whose correlation exceeds
// 0.9 in size (the pairs a report flags).
std::vector<std::string> strongCorrelations(const std::vector<std::string>& names, const Eigen::MatrixXd& covariance, size_t count);
// The correlation of estimates a and b (1 on the diagonal).
double correlationOf(const IdentificationResult& result, Eigen::Index a, Eigen::Index b);
}  // namespace mtacc
