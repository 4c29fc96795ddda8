#pragma once
// Monte Carlo over tolerance limits (seed 000 §3.11): errors drawn uniformly within limits,
// random phases for higher harmonics, and box-plot statistics of a result.
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

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
  std::vector<std::string> leftOut;  // entries for axes the machine lacks (bundled limits only)
};

// Where the range-relative limits (.lin, .<k>harm) of each commanded axis run: its range on the
// path. An axis that does not move on the path has no range to scale by (seed 000 eq. 3.66
// divides by it); its limits are taken over its travel instead (or one turn for a continuous
// rotary axis), and `notes` says so for every such axis that has a range-relative limit.
std::vector<AxisSpan> monteCarloSpans(const Machine& machine, const ErrorLimits& limits, const ConeMotion& motion,
                                      std::vector<std::string>& notes);

// Draws one set of errors within the limits; `drawn`, when given, receives each limit's drawn
// value (mm or rad, in the order of limits.limits).
ErrorModel sampleErrors(const Machine& machine, const ErrorLimits& limits, const std::vector<AxisSpan>& spans,
                        std::mt19937_64& rng, std::vector<double>* drawn = nullptr);

struct ConeMonteCarlo {
  std::vector<double> formErrors;  // mm, one per sample
  BoxStatistics statistics;
  Eigen::MatrixXd drawn;           // samples x limits: each limit's drawn value, mm or rad
  std::vector<std::string> notes;  // limits scaled over the travel (see monteCarloSpans)
};
ConeMonteCarlo coneMonteCarlo(std::shared_ptr<const Machine> machine, const ErrorLimits& limits, const ConeSpec& spec,
                              const ConePath& path, const ConeMotion& motion, int samples, std::uint64_t seed,
                              const std::function<void(int, int)>& progress = {});

}  // namespace mtacc
