// Writes a volume mesh as a Gmsh 2.2 ASCII file, which io::readGmsh and Gmsh itself read back.
#pragma once

#include <ostream>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::io {

/// The nodes (with the mesh's node numbers) and elements (tetrahedra, then the other cells,
/// numbered from 1) of `mesh`, all in physical volume 1.
void writeGmsh(const core::Mesh& mesh, std::ostream& out);

/// The same into the file at `path`; throws std::runtime_error naming it when it cannot be
/// written.
void writeGmshFile(const core::Mesh& mesh, const std::string& path);

}  // namespace deformable_sim::io
