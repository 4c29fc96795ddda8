#include "mtacc/procedures/ballbar_seed002.hpp"

#include "mtacc/core/input_error.hpp"

namespace mtacc {

Seed002Deviations identifySeed002(const Seed002Eccentricities& e, const Seed002Setup& s) {
  if (s.zC1 == s.zC || s.rB2 == s.rB || s.rB == 0.0 || s.rC == 0.0)
    throw InvalidInput(
        "seed 002 identification needs Z_C' != Z_C, R_B'' != R_B and non-zero R_B, R_C: otherwise the twelve errors are not separable");
  const double dz = s.zC1 - s.zC;
  const double slopeX = (e.cr1Ex - e.crEx) / dz;  // beta_CZ, Eq 20
  const double slopeY = (e.crEy - e.cr1Ey) / dz;  // alpha_CZ, Eq 22
  Seed002Deviations d{};
  d.gammaXB = -e.byEx / s.rB;                                                             // Eq 17
  d.dzBT = e.bxEx;                                                                        // Eq 18
  d.dxCZ = e.crEx + e.bxEz - s.zC * slopeX;                                               // Eq 19
  d.betaCZ = slopeX;                                                                      // Eq 20
  d.betaYZ = slopeX - e.caEx / s.rC;                                                      // Eq 21
  d.alphaCZ = slopeY;                                                                     // Eq 22
  d.alphaYZ = slopeY + e.caEy / s.rC;                                                     // Eq 23
  d.alphaXB = e.byEz / s.rB - e.caEy / s.rC - slopeY;                                     // Eq 24
  d.dxBT = e.bxEz + s.rB * (e.cr2Ex - e.cr1Ex) / (s.rB2 - s.rB);                          // Eq 25
  d.betaXB = (e.cr1Ex - e.cr2Ex) / (s.rB - s.rB2) - slopeX + e.caEx / s.rC;               // Eq 26
  d.alphaBT = (e.cr2Ey - e.cr1Ey) / (s.rB - s.rB2) - e.byEz / s.rB;                       // Eq 27
  d.dyCZ = s.rB * (e.cr1Ey - e.cr2Ey) / (s.rB2 - s.rB) + (s.zC1 * e.crEy - s.zC * e.cr1Ey) / dz;  // Eq 28
  return d;
}

}  // namespace mtacc
