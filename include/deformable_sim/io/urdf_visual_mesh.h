// The visual meshes of a robot description's link as one surface: what a body made from a link
// (`mesh: {urdf_link: name, ..}`) is voxelized from.
#pragma once

#include <string>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/io/triangle_mesh_reader.h"
#include "deformable_sim/io/urdf_shapes.h"

namespace deformable_sim::io {

/// The triangles of every <visual><geometry><mesh> of `link`, scaled and posed in the link's
/// frame, as one surface. `package://` URIs through `resolver`, relative paths against
/// `base_directory`. Throws UrdfError when the text is not a valid URDF or the link is missing
/// or has no visual mesh, TriangleMeshError (naming the file) when a mesh cannot be read.
core::TriangleMesh readVisualMesh(const std::string& urdf_xml, const std::string& link,
                                  const PackageResolver& resolver = {},
                                  const std::string& base_directory = "");

}  // namespace deformable_sim::io
