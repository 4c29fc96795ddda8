#pragma once
// Measurement uncertainty of machine-tool tests after ISO/TR 230-9 (the GUM applied to the ISO 230
// tests): the instrument and the environment of a test, each contributor's standard uncertainty
// from them, and the expanded uncertainty U (k = 2) of each result they enter. The contributors and
// how each enters each quantity are in docs/conventions.md ("Measurement uncertainty").
#include <string>
#include <vector>

#include "mtacc/procedures/iso230_2.hpp"

namespace mtacc {

// A reading and the half-width of its error bound (a rectangular distribution: u = a / sqrt 3).
struct BoundedValue {
  double value = 0, halfWidth = 0;
};

enum class InstrumentType {
  Laser,  // a laser interferometer with environmental compensation of its wavelength
  Scale,  // a reference scale or encoder (no wavelength)
  Angle,  // an angular instrument for a rotary axis (angular interferometer, autocollimator and polygon)
};

// Lengths in mm, angles in rad, temperatures in C, pressure in Pa, humidity in %, coefficients in 1/K.
struct MeasurementConditions {
  std::string instrument = "laser interferometer";
  InstrumentType type = InstrumentType::Laser;
  double calibrationRelative = 0.5e-6;  // U (k = 2) of the instrument, length-proportional part
  double calibrationConstant = 0;       // U (k = 2), constant part (mm or rad)
  BoundedValue airTemperature{20, 0.2}, airPressure{101325, 100}, airHumidity{50, 6};
  double airTemperatureChange = 0, airPressureChange = 0;  // during the test: K, Pa (dead path)
  double deadPath = 0;
  double wavelengthNm = 632.99;
  BoundedValue machineTemperature{20, 1.0};
  BoundedValue expansion{11.5e-6, 2e-6};
  double misalignment = 0.5;  // lateral offset of the beam (or scale) over the measured length
  double drift = 0;           // E_VE: the environmental variation error found by a drift test
  std::vector<std::string> defaulted;  // keys the user did not give (their defaults above apply)
  int typeLine = 0;                    // the line of `type` in its file, 0 when not given
};

struct UncertaintyContributor {
  std::string symbol;   // u_DEVICE, u_M,MACHINE, ...
  std::string source;   // what it comes from, with the input values
  double standard = 0;  // standard uncertainty at the measured length, mm or rad
  bool defaulted = false;
  std::vector<std::string> quantities;  // the results it enters
};

struct QuantityUncertainty {
  std::string quantity;  // A, E, ...
  double value = 0;      // the result, mm or rad
  double statistical = 0;  // from the finite number of cycles, mm or rad
  double combined = 0;   // u_c, mm or rad
  double expanded = 0;   // U = 2 u_c
};

struct UncertaintyBudget {
  double measuredLength = 0;  // the span of the targets, mm or rad
  std::vector<UncertaintyContributor> contributors;
  std::vector<QuantityUncertainty> quantities;

  const QuantityUncertainty& at(const std::string& quantity) const;  // throws std::out_of_range
};

// The budget of every ISO 230-2 axis value of the test (A, A↑, A↓, B, E, E↑, E↓, M, R, R↑, R↓).
// Throws InvalidInput when the instrument does not suit the axis (a length instrument on a rotary
// axis or an angular one on a linear axis).
UncertaintyBudget positioningUncertainty(const PositioningTest& test, const PositioningResult& result,
                                         const MeasurementConditions& conditions);

// The budget of results that are ranges of readings (the rotary-axis tests, ISO 230-1's
// straightness and angular deviations): the instrument's standard uncertainty per reading u_r
// (twice in a range, not averaging out: sqrt 2 u_r), the environmental variation error E_VE
// (E_VE / sqrt 3) and the scatter of the means compared (sqrt 2 s / sqrt N, 0 where the test has
// no repeated runs). Values and uncertainties in mm or rad.
struct RangeReadings {
  std::string instrument;           // what reads, for the budget's source line
  double instrumentStandard = 0;    // u_r
  bool instrumentDefaulted = false;
  double drift = 0;                 // E_VE
  bool driftDefaulted = false;
  bool environmentalVariation = true;  // false: the test measures the drift itself (ISO 230-3)
  double scatter = 0;               // s of one reading
  int readingsPerMean = 1;          // N
  const char* unit = "um";          // of the source lines
  double unitScale = 1e3;           // per mm or rad
};
UncertaintyBudget rangeUncertainty(const std::vector<std::pair<std::string, double>>& values, double measuredLength,
                                   const RangeReadings& readings);

}  // namespace mtacc
