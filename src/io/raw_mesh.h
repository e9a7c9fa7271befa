// Private to the mesh readers: what a reader collects from its file(s) before validation, the
// shared validation/repair step that turns it into a core::Mesh, and a line reader that keeps
// track of line numbers so every error can point at the offending line.
#pragma once

#include <Eigen/Core>
#include <array>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "deformable_sim/io/mesh_reader.h"

namespace deformable_sim::io::internal {

struct RawNode {
  long number = 0;  // the file's own node number
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  long line = 0;           // where the number is (for duplicates)
  long position_line = 0;  // where the coordinates are (Gmsh 4.1 puts them on another line)
};

// A volume element: a tetrahedron (4 nodes), pyramid (5), wedge (6) or hexahedron (8).
struct RawElement {
  long number = 0;                 // the file's own element number
  int size = 4;                    // number of nodes
  std::array<long, 8> nodes = {};  // file node numbers, as listed
  long line = 0;
};

// Nodes and volume elements exactly as listed in the file(s), unvalidated. TetGen keeps nodes
// and elements in two files, so each has its own path for the messages.
struct RawMesh {
  std::string node_path;
  std::string element_path;
  std::vector<RawNode> nodes;
  std::vector<RawElement> elements;
  long element_section_line = 0;  // header of the element list, for "no volume elements" errors
  long skipped_elements = 0;      // lower-dimensional elements the reader ignored
};

// Validates `raw` (finite coordinates, unique node numbers, known and distinct element nodes,
// non-degenerate elements, at least one) and repairs what can be repaired without guessing (drops
// unused nodes, reorients elements listed in mirrored order), one warning per kind of repair.
// Throws MeshError naming file, line and node/element number.
MeshReadResult finalizeMesh(const RawMesh& raw);

// "path, line 12: message"
std::string located(const std::string& path, long line, const std::string& message);

// Reads a text file (or stream) one non-blank line at a time and splits it into
// whitespace-separated tokens. Parse errors are thrown as MeshError at the current line.
class LineReader {
 public:
  // comment_char starts a comment that runs to the end of the line ('\0': no comments).
  // Throws MeshError naming the path when the file cannot be opened.
  explicit LineReader(std::string path, char comment_char = '\0');
  // Reads `stream` (kept by reference); `path` names it in messages.
  LineReader(std::string path, std::istream& stream, char comment_char = '\0');

  // Advances to the next line holding at least one token; false at the end of the file.
  bool next();

  const std::string& path() const { return path_; }
  long lineNumber() const { return line_number_; }
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view token(std::size_t i) const { return tokens_[i]; }

  // Throws unless the current line has exactly `count` tokens; `what` describes them.
  void expectCount(std::size_t count, const std::string& what) const;

  // Token i as a number; `what` names it in the error ("node number", "x coordinate").
  long integer(std::size_t i, const std::string& what) const;
  long nonNegative(std::size_t i, const std::string& what) const;
  double real(std::size_t i, const std::string& what) const;

  // Prefixes later errors on this line with e.g. "node 41: "; cleared by next().
  void setContext(std::string context) { context_ = std::move(context); }

  // Throws MeshError "path, line N: [context: ]message".
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string path_;
  char comment_char_;
  std::ifstream file_;    // when reading a file
  std::istream* stream_;  // file_ or the caller's stream
  std::string line_;
  std::vector<std::string_view> tokens_;  // views into line_
  std::string context_;
  long line_number_ = 0;
};

}  // namespace deformable_sim::io::internal
