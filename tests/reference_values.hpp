#pragma once
// A number a source document prints, compared with mtacc's and recorded as a test property;
// scripts/reference_results.py gathers the properties of every Seed* test into
// docs/reference-results.md, so the document is the tests' own output and cannot drift.
#include <string>

namespace mtacc::test {

struct Printed {
  std::string seed;      // "000" ... "004"
  std::string where;     // table or section and the seed's line, "Table 3.4, L4034"
  std::string quantity;  // what the number is, "form error, C0Y = 30 urad"
  double value;
  int decimals;          // as printed
  std::string unit;
};

// A statement the seed prints in words rather than as one number ("8.4 um lies between the
// median and the upper quartile"), with what mtacc's computation says about it.
struct Statement {
  std::string seed, where, quantity;
  std::string printed;  // the claim with the seed's numbers, "7.9 <= 8.4 <= 10.0"
};
// Reproduced when mtacc's computation bears the statement out (`holds`), which the test asserts.
void expectStatementHolds(const Statement& statement, bool holds, const std::string& mtacc, const std::string& why);
// A known difference: mtacc's computation contradicts the statement, for `reason`; asserted, so
// one that starts to hold fails until it is moved to expectStatementHolds.
void expectStatementFails(const Statement& statement, bool holds, const std::string& mtacc, const std::string& reason);

// Reproduced: |mtacc - printed| <= tolerance, which `why` justifies (usually half the last
// printed digit).
void expectReproduced(const Printed& printed, double mtacc, double tolerance, const std::string& why);

// Not reproduced, for `reason`. Today's value is pinned to +-pin so that a change is noticed,
// and it must stay more than half the last printed digit away from the printed value: one that
// starts to agree has to be moved to expectReproduced.
void expectKnownDifference(const Printed& printed, double mtacc, double today, double pin, const std::string& reason);

// Input echoed: a number the seed prints that mtacc reads (or derives from what it reads by a
// rule the seed states) and writes back, e.g. a test piece's own geometry. Checked like a
// reproduction, so the data entry stays right, but counted apart: it reproduces no computation.
void expectInputEchoed(const Printed& printed, double mtacc, double tolerance, const std::string& why);

// Self-consistent: `injected` (a value the seed gives, or the test's own truth) simulated by
// mtacc and recovered by mtacc's identification or decomposition within `tolerance`. A useful
// check of the method, not agreement with a published result.
void expectSelfConsistent(const Printed& injected, double recovered, double tolerance, const std::string& why);

// A printed number the library does not compute, listed with the reason: what input is
// missing and where the seed fails to give it, or what is not built.
void recordNotComputed(const Printed& printed, const std::string& reason);

}  // namespace mtacc::test
