#pragma once
// Seed 002 §5.2: closed-form identification of the twelve location errors of a multi-tasking
// machine (B swivel head, C work spindle) from the eccentricities of six ball-bar runs,
// Eqs 17-28. All lengths in one unit (mm), angles come out in rad.
namespace mtacc {

// Eccentricities (first-harmonic centre offsets) of the six runs: B X-direction, B
// Y-direction, C axial, and C radial at (Z_C, R_B), (Z_C', R_B) and (Z_C', R_B'').
struct Seed002Eccentricities {
  double bxEx, bxEz;
  double byEx, byEz;
  double caEx, caEy;
  double crEx, crEy;     // C radial at (Z_C, R_B)
  double cr1Ex, cr1Ey;   // C radial at (Z_C', R_B)
  double cr2Ex, cr2Ey;   // C radial at (Z_C', R_B'')
};

struct Seed002Setup {
  double rB, rB2;  // T-ball distance from the B centre: R_B and R_B''
  double rC;       // W-ball radius on the C table
  double zC, zC1;  // W-ball heights Z_C and Z_C'
};

// The seed's names (Table 1); ISO equivalents in docs/conventions.md (alias table).
struct Seed002Deviations {
  double dxBT, dzBT, alphaBT, alphaXB, betaXB, gammaXB, alphaYZ, betaYZ, dxCZ, dyCZ, alphaCZ, betaCZ;
};

// Throws InvalidInput when the set-up cannot separate them (Z_C' = Z_C, R_B'' = R_B,
// R_B = 0 or R_C = 0).
Seed002Deviations identifySeed002(const Seed002Eccentricities& e, const Seed002Setup& s);

}  // namespace mtacc
