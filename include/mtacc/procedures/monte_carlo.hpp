#pragma once
// Monte Carlo over tolerance limits (seed 000 §3.11): errors drawn uniformly within limits,
// random phases for higher harmonics, and box-plot statistics of a result.
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "mtacc/core/statistics.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/procedures/cone.hpp"

namespace mtacc {

struct ErrorLimit {
  enum Kind { Location, Linear, Reversal, Cyclic, Harmonic };
  std::string key;  // as written, e.g. "EYX.2harm"
  Kind kind = Location;
  int axis = -1;
  int component = 0;
  int order = 1;     // Harmonic
  double pitch = 0;  // Cyclic, mm or rad
  double lower = 0, upper = 0;  // mm or rad
  Parameter location;           // Location
};

struct ErrorLimits {
  std::string file;
  std::vector<ErrorLimit> limits;
};

// `spans`: where linear and harmonic errors run, per commanded axis (on a test path, or the travel).
ErrorModel sampleErrors(const Machine& machine, const ErrorLimits& limits, const std::vector<AxisSpan>& spans,
                        std::mt19937_64& rng);

struct ConeMonteCarlo {
  std::vector<double> formErrors;  // mm, one per sample
  BoxStatistics statistics;
};
ConeMonteCarlo coneMonteCarlo(std::shared_ptr<const Machine> machine, const ErrorLimits& limits, const ConeSpec& spec,
                              const ConePath& path, const ConeMotion& motion, int samples, std::uint64_t seed,
                              const std::function<void(int, int)>& progress = {});

}  // namespace mtacc
