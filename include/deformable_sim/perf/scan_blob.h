// The voxelization benchmark's surface: a closed, bumpy and noisy blob of about 70k triangles, as
// a scanned part comes (uneven triangles, slivers at the poles, a rough skin) — built in code, the
// same on every machine.
#pragma once

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::perf {

/// A sphere of radius 0.1 m about the origin with lobes of up to 20 % of the radius and a random
/// (seeded) radial roughness of 0.3 %, as a UV sphere of `rings` x `segments` quads (poles
/// merged): 2 segments (rings - 1) triangles, facing outwards. 150 x 234 gives 69,732.
core::TriangleMesh makeScanBlob(int rings = 150, int segments = 234);

}  // namespace deformable_sim::perf
