#pragma once
// What the readers of measured points (point clouds, cone points, artefact features) accept.
// Private to the io module.

namespace mtacc {

// Any coordinate of a point measured on a part or an artefact (mm): 10 m, beyond any machine's
// work zone; a larger one is a unit mistake.
constexpr double kLargestMeasuredCoordinate = 1e4;

}  // namespace mtacc
