// TetGen .node/.ele reader. Node numbers are taken as written (TetGen numbers from 0 or from 1)
// and the .ele file refers to them by those numbers, so no renumbering guess is needed.
#include <string>

#include "deformable_sim/io/mesh_reader.h"
#include "raw_mesh.h"

namespace deformable_sim::io {
namespace {

using internal::LineReader;
using internal::RawElement;
using internal::RawMesh;
using internal::RawNode;

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "beam", "beam.node" and "beam.ele" all name the pair beam.node + beam.ele.
std::string prefixOf(const std::string& path) {
  static const std::string kExtensions[] = {".node", ".ele"};
  for (const std::string& extension : kExtensions) {
    if (endsWith(path, extension)) return path.substr(0, path.size() - extension.size());
  }
  return path;
}

std::string withOptional(long count, const std::string& what) {
  if (count == 0) return "";
  return ", " + std::to_string(count) + " " + what;
}

// Reads the header line of a TetGen file; a file with nothing but comments has none.
void readHeader(LineReader& in, const std::string& expected) {
  if (!in.next()) {
    throw MeshError(in.path() + ": the file is empty (expected the header '" + expected + "')");
  }
}

// Moves to entry `index` (0-based) of `count` announced on `header_line`; the file must not end.
void nextEntry(LineReader& in, long index, long count, const std::string& what, long header_line) {
  if (!in.next()) {
    in.fail("the file ends after " + std::to_string(index) + " of the " + std::to_string(count) +
            " " + what + "s announced on line " + std::to_string(header_line) + " (" + what + " " +
            std::to_string(index + 1) + " of " + std::to_string(count) + " is missing)");
  }
  in.setContext(what + " " + std::string(in.token(0)));
}

void expectNoMore(LineReader& in, long count, const std::string& what, long header_line) {
  if (in.next()) {
    in.setContext(what + " " + std::string(in.token(0)));
    in.fail("more " + what + "s than the " + std::to_string(count) + " announced on line " +
            std::to_string(header_line));
  }
}

void readNodeFile(LineReader& in, RawMesh& raw) {
  readHeader(in, "npoints dim nattributes boundarymarker");
  in.expectCount(4, "number of points, dimension, number of attributes, boundary marker flag");
  const long count = in.nonNegative(0, "number of points");
  const long dimension = in.integer(1, "dimension");
  const long num_attributes = in.nonNegative(2, "number of attributes");
  const long num_markers = in.nonNegative(3, "boundary marker flag");
  if (dimension != 3) in.fail("dimension must be 3, found " + std::to_string(dimension));
  if (num_markers > 1) {
    in.fail("boundary marker flag must be 0 or 1, found " + std::to_string(num_markers));
  }
  const long header_line = in.lineNumber();

  const std::string layout = "node number, x, y, z" + withOptional(num_attributes, "attributes") +
                             (num_markers == 1 ? ", boundary marker" : "");
  for (long i = 0; i < count; ++i) {
    nextEntry(in, i, count, "node", header_line);
    in.expectCount(std::size_t{4} + num_markers + static_cast<std::size_t>(num_attributes), layout);
    RawNode node;
    node.number = in.integer(0, "node number");
    node.position = {in.real(1, "x coordinate"), in.real(2, "y coordinate"),
                     in.real(3, "z coordinate")};
    for (long a = 0; a < num_attributes; ++a) in.real(4 + a, "attribute");
    if (num_markers == 1) in.integer(4 + num_attributes, "boundary marker");
    node.line = node.position_line = in.lineNumber();
    raw.nodes.push_back(node);
  }
  expectNoMore(in, count, "node", header_line);
}

void readElementFile(LineReader& in, RawMesh& raw) {
  readHeader(in, "ntetrahedra nodes_per_tetrahedron nattributes");
  in.expectCount(3, "number of tetrahedra, nodes per tetrahedron, number of attributes");
  const long count = in.nonNegative(0, "number of tetrahedra");
  const long nodes_per_tet = in.integer(1, "nodes per tetrahedron");
  const long num_attributes = in.nonNegative(2, "number of attributes");
  if (nodes_per_tet == 10) {
    in.fail("10-node (quadratic) tetrahedra are not supported yet; only 4-node tetrahedra are");
  }
  if (nodes_per_tet != 4) {
    in.fail("nodes per tetrahedron must be 4 or 10, found " + std::to_string(nodes_per_tet));
  }
  const long header_line = in.lineNumber();
  raw.element_section_line = header_line;

  const std::string layout =
      "element number, 4 node numbers" + withOptional(num_attributes, "attributes");
  for (long i = 0; i < count; ++i) {
    nextEntry(in, i, count, "element", header_line);
    in.expectCount(std::size_t{5} + static_cast<std::size_t>(num_attributes), layout);
    RawElement tet;
    tet.number = in.integer(0, "element number");
    for (int k = 0; k < 4; ++k) tet.nodes[k] = in.integer(1 + k, "node number");
    for (long a = 0; a < num_attributes; ++a) in.real(5 + a, "attribute");
    tet.line = in.lineNumber();
    raw.elements.push_back(tet);
  }
  expectNoMore(in, count, "element", header_line);
}

}  // namespace

MeshReadResult readTetGen(const std::string& path) {
  const std::string prefix = prefixOf(path);
  RawMesh raw;
  raw.node_path = prefix + ".node";
  raw.element_path = prefix + ".ele";
  LineReader nodes(raw.node_path, '#');
  readNodeFile(nodes, raw);
  LineReader elements(raw.element_path, '#');
  readElementFile(elements, raw);
  return internal::finalizeMesh(raw);
}

MeshReadResult readTetGen(std::istream& node_stream, std::istream& element_stream,
                          const std::string& name) {
  RawMesh raw;
  raw.node_path = name + ".node";
  raw.element_path = name + ".ele";
  LineReader nodes(raw.node_path, node_stream, '#');
  readNodeFile(nodes, raw);
  LineReader elements(raw.element_path, element_stream, '#');
  readElementFile(elements, raw);
  return internal::finalizeMesh(raw);
}

}  // namespace deformable_sim::io
