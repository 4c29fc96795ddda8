#pragma once
// The refractive index of air, which a laser interferometer's environmental compensation divides
// its vacuum wavelength by: the modified Edlén equation of the NIST Engineering Metrology Toolbox
// (J. A. Stone and J. H. Zimmerman, "Index of Refraction of Air", App. A-IV: Birch and Downs,
// Metrologia 30, 155 (1993) and 31, 315 (1994), with NIST's water-vapour term) and the saturation
// vapour pressure of IAPWS-IF97 (App. A-I). Its sensitivities give a compensation's uncertainty
// from the uncertainties of its air sensors.
namespace mtacc {

struct AirConditions {
  double temperatureC = 20.0;
  double pressurePa = 101325.0;
  double relativeHumidityPercent = 50.0;
};

constexpr double kHeliumNeonWavelengthNm = 632.99;  // vacuum wavelength of a He-Ne laser

// Valid (App. VI) for 300-1700 nm, 60-120 kPa, 0-40 C, 0-100 %; throws InvalidInput outside.
double airRefractiveIndex(const AirConditions& air, double vacuumWavelengthNm = kHeliumNeonWavelengthNm);
// Saturation vapour pressure of water over liquid water (Pa) at a temperature in C.
double saturationVapourPressure(double temperatureC);

// dn/dt (1/K), dn/dp (1/Pa), dn/dRH (1/%) at the conditions, by central differences of the
// equation (its curvature is negligible over the steps used).
struct RefractiveIndexSensitivities {
  double perKelvin = 0, perPascal = 0, perPercent = 0;
};
RefractiveIndexSensitivities airRefractiveIndexSensitivities(const AirConditions& air,
                                                             double vacuumWavelengthNm = kHeliumNeonWavelengthNm);

}  // namespace mtacc
