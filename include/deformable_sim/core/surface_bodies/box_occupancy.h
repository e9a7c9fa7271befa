// How much of a cube a surface encloses: the cube is cut into eighths, again and again where a
// triangle may cross a part, and every part that no triangle crosses (or that is as small as the
// levels allow) counts as inside when its centre is inside (InsideTest: the winding number at it
// is at least 1/2).
// Sampling only where the surface passes keeps the count of winding-number queries near the
// surface's area in parts, not the cube's volume.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

/// Whether a point, m, is inside the surface.
using InsideTest = std::function<bool(const Eigen::Vector3d&)>;

/// Whether triangle t of `surface` may cross the cube [min, min + size]: its bounding box and
/// its plane both meet the cube (grown by `margin`, m). Conservative: never false for a triangle
/// that does cross.
bool triangleMayCrossCube(const TriangleMesh& surface, int t, const Eigen::Vector3d& min,
                          double size, double margin);

/// The fraction of the cube [min, min + size] inside the surface, in [0, 1], to a resolution of
/// size / 2^levels near the surface. `candidates`: the triangles that may cross the cube.
double occupiedFraction(const TriangleMesh& surface, const InsideTest& inside,
                        const std::vector<int>& candidates, const Eigen::Vector3d& min, double size,
                        int levels);

/// The same for each octant of the cube (octant o at min + size / 2 (o & 1, o >> 1 & 1,
/// o >> 2 & 1)), to a resolution of size / 2^levels (levels >= 1).
std::array<double, 8> octantFractions(const TriangleMesh& surface, const InsideTest& inside,
                                      const std::vector<int>& candidates,
                                      const Eigen::Vector3d& min, double size, int levels);

}  // namespace deformable_sim::core
