#pragma once
// How sampled values are joined: straight lines, or a cubic spline (its end conditions are the
// interpolant's to state: natural for error tables, not-a-knot for recorded signals).
namespace mtacc {

enum class Interpolation { Linear, CubicSpline };

}  // namespace mtacc
