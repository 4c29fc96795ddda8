#include "mtacc/procedures/air_refractive_index.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

void requireWithin(double value, double low, double high, const char* what, const char* unit) {
  if (!(value >= low && value <= high))
    throw InvalidInput(fmt::format("the refractive index of air: {} {:g} {} is outside the equation's range {:g} to {:g} {}", what,
                                   value, unit, low, high, unit));
}

}  // namespace

double saturationVapourPressure(double temperatureC) {
  constexpr double K[10] = {1.16705214528E+03, -7.24213167032E+05, -1.70738469401E+01, 1.20208247025E+04, -3.23255503223E+06,
                            1.49151086135E+01, -4.82326573616E+03, 4.05113405421E+05,  -2.38555575678E-01, 6.50175348448E+02};
  const double T = temperatureC + 273.15;
  const double omega = T + K[8] / (T - K[9]);
  const double a = omega * omega + K[0] * omega + K[1];
  const double b = K[2] * omega * omega + K[3] * omega + K[4];
  const double c = K[5] * omega * omega + K[6] * omega + K[7];
  const double x = -b + std::sqrt(b * b - 4 * a * c);
  return 1e6 * std::pow(2 * c / x, 4);
}

double airRefractiveIndex(const AirConditions& air, double vacuumWavelengthNm) {
  requireWithin(vacuumWavelengthNm, 300, 1700, "wavelength", "nm");
  requireWithin(air.pressurePa, 60e3, 120e3, "pressure", "Pa");
  requireWithin(air.temperatureC, 0, 40, "temperature", "C");
  requireWithin(air.relativeHumidityPercent, 0, 100, "relative humidity", "%");
  constexpr double A = 8342.54, B = 2406147, C = 15998, D = 96095.43, E = 0.601, F = 0.00972, G = 0.003661;
  const double t = air.temperatureC, p = air.pressurePa;
  const double sigma2 = 1.0 / std::pow(vacuumWavelengthNm * 1e-3, 2);  // um^-2
  const double standardRefractivity = 1e-8 * (A + B / (130 - sigma2) + C / (38.9 - sigma2));
  const double density = (1 + 1e-8 * (E - F * t) * p) / (1 + G * t);
  const double vapourPressure = air.relativeHumidityPercent / 100 * saturationVapourPressure(t);
  const double dryRefractivity = p * standardRefractivity * density / D;
  return 1 + dryRefractivity - 1e-10 * (292.75 / (t + 273.15)) * (3.7345 - 0.0401 * sigma2) * vapourPressure;
}

RefractiveIndexSensitivities airRefractiveIndexSensitivities(const AirConditions& air, double vacuumWavelengthNm) {
  airRefractiveIndex(air, vacuumWavelengthNm);  // the range check
  // The centre kept one step inside the range, so that both sides can be evaluated at its edges.
  const AirConditions centre{std::clamp(air.temperatureC, 0.01, 39.99), std::clamp(air.pressurePa, 60010.0, 119990.0),
                             std::clamp(air.relativeHumidityPercent, 0.1, 99.9)};
  const auto slope = [&](auto shift, double step) {
    AirConditions up = centre, down = centre;
    shift(up, step);
    shift(down, -step);
    return (airRefractiveIndex(up, vacuumWavelengthNm) - airRefractiveIndex(down, vacuumWavelengthNm)) / (2 * step);
  };
  return {slope([](AirConditions& a, double h) { a.temperatureC += h; }, 0.01),
          slope([](AirConditions& a, double h) { a.pressurePa += h; }, 10.0),
          slope([](AirConditions& a, double h) { a.relativeHumidityPercent += h; }, 0.1)};
}

}  // namespace mtacc
