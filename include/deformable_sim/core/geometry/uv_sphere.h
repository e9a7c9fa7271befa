// A UV sphere: rings of latitude between two poles, each ring's vertices joined to the next ring's
// by quads (as two triangles), each pole a single vertex joined to its ring by a fan; facing
// outwards. The radius may vary with the direction, for a bumpy blob as well as a ball.
#pragma once

#include <functional>

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

/// The distance from the centre, m, along the direction of polar angle `polar` (from +z) and
/// `azimuth` (from +x towards +y), rad.
using SphereRadius = std::function<double(double polar, double azimuth)>;

/// A UV sphere about the origin of `rings` bands (rings - 1 rings of `segments` vertices between
/// the poles) and `segments` around: 2 segments (rings - 1) triangles, counter-clockwise seen from
/// outside. Its vertices are the south pole (polar pi, on -z), the rings from the south, ring r at
/// polar pi (1 - r / rings) with vertex s at azimuth 2 pi s / segments, then the north pole
/// (polar 0, on +z); `radius` is asked once per vertex, in that order.
TriangleMesh uvSphere(int rings, int segments, const SphereRadius& radius);

}  // namespace deformable_sim::core
