// What is wrong with a surface before it is voxelized, what was done about it, and the warnings
// that say so. Real scans have holes, stray and repeated triangles, pieces facing the wrong way
// and parts that pass through each other; the voxelizer judges inside by the generalized winding
// number (core/geometry/winding_number.h), which bears holes and crossings, so those are only
// reported, while what would mislead it (repeated triangles, triangles or whole shells facing
// inwards) is repaired here.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/geometry/self_crossings.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

struct SurfaceCheck {
  int zero_area = 0;        ///< triangles dropped: corners that coincide or lie on a line
  int duplicates = 0;       ///< triangles dropped: the same three corners as another
  int open_edges = 0;       ///< edges of one triangle only: the rims of holes
  int overused_edges = 0;   ///< edges of three or more triangles
  int misoriented = 0;      ///< triangles turned to face the way their neighbours face
  bool inside_out = false;  ///< the whole surface enclosed a negative volume and was turned
  int shells = 0;           ///< separate surfaces (groups of triangles joined through edges)
  int voids = 0;            ///< closed shells facing inwards inside another: hollows, kept
  int turned_shells = 0;    ///< closed shells facing inwards inside nothing, turned outwards
  SelfCrossings crossings;  ///< triangles that pass through each other
};

/// Readies `surface` (finite vertices, valid indices) for the voxelizer and counts what it finds:
/// drops triangles of zero area and repeated ones (one copy of a triangle repeated the same way is
/// kept; a pair facing opposite ways cancels and both go), turns triangles that face against
/// their neighbours, turns the whole surface when it encloses a negative volume, then turns each
/// closed shell that still faces inwards unless it lies inside another shell (then it is a void),
/// and drops the vertices no triangle uses. Open and overused edges and crossing triangles are
/// counted only. `zero_area_dropped` (a reader's triangles whose corners coincided) is added to
/// the count of zero-area ones.
SurfaceCheck checkSurface(TriangleMesh& surface, int zero_area_dropped = 0);

/// One warning per kind of problem `check` found, e.g. "3 open edges (the surface has holes;
/// inside is judged by the winding number, volume may be off)" or "12 triangles dropped: 8 with
/// zero area, 4 duplicates"; none for a clean surface. Shells are named only when one faced
/// inwards (a void, or turned): shells apart are the separate pieces the voxelizer names.
std::vector<std::string> surfaceWarnings(const SurfaceCheck& check);

}  // namespace deformable_sim::core
