#include "mtacc/identification/fit_quality.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/special_functions/gamma.hpp>
#include <fmt/format.h>

#include "mtacc/core/units.hpp"

namespace mtacc {

IdentificationQuality fitQuality(const IdentificationResult& r, std::optional<double> statedNoise, double uncertaintyFraction) {
  IdentificationQuality q;
  if (!r.converged) q.warnings.push_back("the solver did not converge; the estimates are not a least-squares solution");
  bool stated = r.degreesOfFreedom > 0 && !r.runs.empty();
  double chiSquare = 0;
  for (size_t k = 0; k < r.runs.size() && stated; ++k) {
    const auto noise = statedNoise ? statedNoise : r.runs[k].noise;
    if (noise) chiSquare += r.runResidualSquares[k] / (*noise * *noise);
    else stated = false;
  }
  if (stated) {
    q.chiSquare = chiSquare;
    q.pValue = boost::math::gamma_q(0.5 * r.degreesOfFreedom, 0.5 * chiSquare);
    if (*q.pValue < kFitSignificance)
      q.warnings.push_back(fmt::format(
          "the residuals are larger than the stated noise explains: chi-square {:.4g} for {} degrees of freedom, "
          "p = {:.2g} (below {:g}); residual sigma {:.3g} um. The data contain errors the parameter set does not "
          "model, outliers, or the noise is understated", chiSquare, r.degreesOfFreedom, *q.pValue, kFitSignificance,
          r.sigma * 1e3));
  }
  for (Eigen::Index k = 0; k < r.uncertainty.size(); ++k) {
    const auto d = r.columns.dimensions[static_cast<size_t>(k)];
    const double plausible = d == Dimension::Length ? kPlausibleLength : kPlausibleAngle;
    if (!(r.uncertainty[k] <= uncertaintyFraction * plausible)) {
      q.poorlyDetermined.push_back(static_cast<size_t>(k));
      q.warnings.push_back(fmt::format(
          "{} is hardly determined: its standard uncertainty {:.4g} {} exceeds {:g} % of its plausible magnitude "
          "{:g} {} (a plan with more motion of the axes it depends on determines it)",
          r.columns.names[static_cast<size_t>(k)], toDisplay(r.uncertainty[k], d), displayUnit(d),
          100 * uncertaintyFraction, toDisplay(plausible, d), displayUnit(d)));
    }
  }
  return q;
}

std::vector<HarmonicEstimate> harmonicEstimates(const IdentificationResult& r) {
  std::vector<HarmonicEstimate> out;
  const auto& names = r.columns.names;
  for (size_t c = 0; c < names.size(); ++c) {
    if (!names[c].ends_with('c') || names[c].rfind(".h") == std::string::npos) continue;
    const std::string base = names[c].substr(0, names[c].size() - 1);
    const auto sine = std::find(names.begin(), names.end(), base + "s");
    if (sine == names.end()) continue;
    const auto i = static_cast<Eigen::Index>(c), j = static_cast<Eigen::Index>(sine - names.begin());
    const double a = r.values[i], b = r.values[j], amplitude = std::hypot(a, b);
    // Gradients of the amplitude and of the phase atan2(-b, a) in (a, b).
    Eigen::Vector2d gAmplitude = Eigen::Vector2d::Zero(), gPhase = Eigen::Vector2d::Zero();
    if (amplitude > 0) {
      gAmplitude = Eigen::Vector2d(a, b) / amplitude;
      gPhase = Eigen::Vector2d(b, -a) / (amplitude * amplitude);
    }
    Eigen::Matrix2d cov;
    cov << r.covariance(i, i), r.covariance(i, j), r.covariance(j, i), r.covariance(j, j);
    out.push_back({base, r.columns.dimensions[c], amplitude, std::sqrt(gAmplitude.dot(cov * gAmplitude)), std::atan2(-b, a),
                   std::sqrt(gPhase.dot(cov * gPhase))});
  }
  return out;
}

std::vector<std::string> strongCorrelations(const std::vector<std::string>& names, const Eigen::MatrixXd& covariance, size_t count) {
  std::vector<std::string> out;
  for (size_t a = 0; a < count; ++a)
    for (size_t b = a + 1; b < count; ++b) {
      const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
      const double c = covariance(ia, ib) / std::sqrt(covariance(ia, ia) * covariance(ib, ib));
      if (std::abs(c) > 0.9) out.push_back(fmt::format("{} and {}: {:.3f}", names[a], names[b], c));
    }
  return out;
}

double correlationOf(const IdentificationResult& r, Eigen::Index a, Eigen::Index b) {
  const double scale = std::sqrt(r.covariance(a, a) * r.covariance(b, b));
  return scale > 0 ? r.covariance(a, b) / scale : (a == b ? 1.0 : 0.0);
}

}  // namespace mtacc
