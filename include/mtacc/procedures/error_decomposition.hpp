#pragma once
// Seed 004 (Andolfatto, Lavernhe, Mayer): the TCP error of a five-axis machine, measured along
// one trajectory at several feeds, split into servo contouring, link, motion, thermal drift and
// dynamic errors (eqs. 6, 10-20), and the statistics of the paper's Tables 1-4 (eqs. 21-23).
// Every series is on the instrument's clock (the traces aligned and resampled onto it), one
// sample a row, the tool relative to the workpiece in the workpiece frame, in mm; held in
// LargeVectors (huge pages for long series).
#include <span>
#include <vector>

#include "mtacc/core/large_vector.hpp"
#include "mtacc/core/transform.hpp"

namespace mtacc {

struct DecompositionTest {
  double feed = 0.0;            // mm/min as programmed (FGROUP: mm and deg mixed, seed 004 O8)
  LargeVector<double> time;     // s, increasing
  LargeVector<double> path;     // length travelled along the encoder path (FGROUP units), not decreasing; for MotionParameter::Path
  LargeVector<Vec3> measured;   // chi: the instrument's reading, set-up removed
  LargeVector<Vec3> encoder;    // chi_enc: the direct kinematics of the encoder positions
  LargeVector<Vec3> nominal;    // chi_nom: the direct kinematics of the interpolator's commands
  LargeVector<Vec3> link;       // delta_l: the identified link errors along the path (eqs. 13-15)
  // The workpiece frame's rotation in the machine frame at each sample (the nominal machine at
  // the encoder positions), for a drift constant in the machine frame; empty: the identity.
  LargeVector<Mat3> workpieceRotation;
  // The axes' acceleration at each sample (the norm over the axes, FGROUP: mm and deg per s^2),
  // for ReferenceFit::Steady; empty: not known, every sample fitted.
  LargeVector<double> acceleration;
};

// Where the thermal drift is constant over a test (eq. 19): in the machine frame, as seed 004
// takes it (the structure warms, the table turns under it), or in the workpiece frame.
enum class DriftFrame { Machine, Workpiece };

// What the motion errors are a function of (O5): the time from the test's first sample to its
// last scaled to [0, 1] (the paper's), or the path travelled, scaled alike. The motion errors
// are errors of the axis positions, so the path maps the same place of the trajectory at every
// feed; time does so only while the feeds share one time law (the dwells, the accelerations and
// the slow-downs at corners take a different share of each test).
enum class MotionParameter { Time, Path };

// Which samples of the reference test the motion errors are fitted to (eq. 17). Seed 004 fits
// them all, taking the reference's dynamic error for negligible; it is so "except locally at the
// start, the end and sharp corners" (L237), where the axes accelerate as hard at the low feed as
// at the others, and the fit carries what it finds there to every feed. Steady leaves out the
// samples where the axes accelerate beyond `steadyShare` of the reference test's largest
// acceleration (the fit still spans them: the motion errors are smooth in the path); where that
// would leave out half the samples or more (a reference accelerating throughout), it fits all.
enum class ReferenceFit { Steady, All };

struct DecompositionOptions {
  int referenceTest = 0;  // the slow test whose error beyond the link errors is all motion error (eq. 16)
  int degree = 20;        // of the Legendre fit of the motion errors in the normalised parameter (eq. 17, O5, O6)
  MotionParameter parameter = MotionParameter::Path;
  DriftFrame driftFrame = DriftFrame::Machine;
  ReferenceFit referenceFit = ReferenceFit::Steady;
  double steadyShare = 0.05;
};

struct DecomposedTest {
  DecompositionTest recorded;    // the test as given: its time, path, chi, chi_enc, chi_nom and delta_l
  LargeVector<Vec3> contouring;  // delta_c = chi_enc - chi_nom (eq. 10)
  // The contouring error as L120 and Fig. 4 define it: delta_c's part orthogonal to the commanded
  // path (its tangent from the nominal trace). NaN where the nominal path stands still (no tangent:
  // in seed 004's chase-the-ball path |tau_nom| stays within 100 um), counted in orthogonalUndefined.
  LargeVector<Vec3> contouringOrthogonal;
  size_t orthogonalUndefined = 0;
  LargeVector<Vec3> motion;      // delta_m: the reference test's fit at this test's normalised parameter
  Vec3 drift = Vec3::Zero();     // td (eq. 18), constant in the drift frame (eq. 19); 0 in the reference test
  bool driftInMachineFrame = false;  // DriftFrame::Machine with the workpiece's rotations given
  LargeVector<Vec3> dynamic;     // delta_d = chi - chi_enc - delta_qs (eq. 20); zero mean (in the drift frame) by construction but in a steady-fitted reference
  size_t leftOutOfFit = 0;       // in the reference test: the samples the motion errors were not fitted to (ReferenceFit::Steady)

  // The drift at sample i in the workpiece frame.
  Vec3 driftAt(size_t i) const { return driftInMachineFrame ? Vec3(recorded.workpieceRotation[i].transpose() * drift) : drift; }
  Vec3 quasiStatic(size_t i) const { return recorded.link[i] + motion[i] + driftAt(i); }  // delta_qs (eq. 12)
};

// What the method cannot split, by construction: a mean of the true dynamic error is booked as
// drift (delta_d has zero mean in every test), and link and motion errors trade content with
// each other (only their sum is fixed by the reference test). Throws InvalidInput on
// series of unequal lengths (a path of another length, or decreasing, when the path is the
// parameter), fewer than two samples, times not increasing, a path that does not advance, a reference test of
// no more samples than the fit has coefficients, or a reference index out of range.
// Each test is moved into its result (DecomposedTest::recorded).
std::vector<DecomposedTest> decomposeErrors(std::vector<DecompositionTest> tests, const DecompositionOptions& options = {});

// delta_c less its component along the tangent of the nominal path (central differences of the
// nominal samples, one-sided at the ends); NaN where the path moves less than `still` (mm) over
// the difference, with `undefined` counting those samples.
LargeVector<Vec3> orthogonalToPath(std::span<const Vec3> deviation, std::span<const Vec3> nominal, size_t& undefined,
                                   double still = 1e-7);

// Eq. 21: the mean over the samples of each contribution's norm over the sum of the norms, in %.
// The printed denominator has three norms (c, qs, d); Table 1 splits qs into l, m, td and its
// rows sum to 100 %, so it used five norms (erratum E1). Both are given; samples where every
// contribution is zero are left out.
struct DecompositionShares {
  double contouring = 0, quasiStatic = 0, dynamic = 0;                      // over |c| + |qs| + |d|
  double splitContouring = 0, link = 0, motion = 0, drift = 0, splitDynamic = 0;  // over |c| + |l| + |m| + |td| + |d|
  double splitOverPrinted = 0;  // the five numerators over the printed denominator: > 100 when l, m, td are not parallel
};
DecompositionShares decompositionShares(const DecomposedTest& test);

// Eq. 22 and Table 4: per direction, the largest absolute value and the root mean square.
struct DirectionStatistics {
  Vec3 maximum = Vec3::Zero();
  Vec3 rms = Vec3::Zero();
};
DirectionStatistics directionStatistics(std::span<const Vec3> series);  // NaN samples left out

// Eq. 23: value = kappa * feed^exponent, least squares on the logarithms. Throws
// InvalidInput for fewer than two feeds, feeds all equal, or a value or feed <= 0.
struct PowerLaw {
  double kappa = 0.0, exponent = 0.0;
  double largestRelativeMisfit = 0.0;  // max |fit / value - 1| over the points
};
PowerLaw fitPowerLaw(const std::vector<double>& feeds, const std::vector<double>& values);

// first * ratio^k for k = 0 .. count - 1: the paper's feed ladder is 1000 mm/min times 1.8^k.
std::vector<double> geometricFeeds(double first, double ratio, int count);

}  // namespace mtacc
