// Readers for volumetric meshes: Gmsh .msh (ASCII 2.2 and 4.1) and TetGen .node/.ele.
//
// Every reader validates what it reads and throws MeshError with a message that names the file,
// the line and (where there is one) the element or node number. Problems that can be repaired
// without guessing are repaired and reported in MeshReadResult::warnings: nodes that no element
// uses are dropped, negatively oriented tetrahedra are reordered.
#pragma once

#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::io {

class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct MeshReadResult {
  core::Mesh mesh;
  std::vector<std::string> warnings;  ///< one sentence per repair, naming file and element/node
};

/// Gmsh ASCII .msh, version 2.2 or 4.1 (detected from $MeshFormat). Volume elements only
/// (lower-dimensional elements such as points, lines and triangles are skipped).
MeshReadResult readGmsh(const std::string& path);
/// The same from a stream; `name` stands for the file in messages.
MeshReadResult readGmsh(std::istream& stream, const std::string& name);

/// TetGen .node/.ele. `path` is either the prefix ("beam" for beam.node + beam.ele) or the path
/// of the .node or the .ele file. Numbering from 0 or from 1, as TetGen allows.
MeshReadResult readTetGen(const std::string& path);
/// The same from two streams; messages name them `name`.node and `name`.ele.
MeshReadResult readTetGen(std::istream& node_stream, std::istream& element_stream,
                          const std::string& name);

/// Picks the reader from the file name: ".msh" -> Gmsh, ".node", ".ele" or no extension ->
/// TetGen. Throws MeshError for anything else.
MeshReadResult readMesh(const std::string& path);

}  // namespace deformable_sim::io
