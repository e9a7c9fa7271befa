// Gmsh ASCII .msh reader, format versions 2.2 and 4.1. Only $MeshFormat, $Nodes and $Elements
// are interpreted; every other section is skipped. Lower-dimensional elements are skipped, linear
// tetrahedra, pyramids, wedges (prisms) and hexahedra are kept, and any other volume element is an
// error (not silently dropped, which would leave holes in the body).
#include <cctype>
#include <string>
#include <string_view>

#include "deformable_sim/io/mesh_reader.h"
#include "raw_mesh.h"

namespace deformable_sim::io {
namespace {

using internal::LineReader;
using internal::located;
using internal::RawElement;
using internal::RawMesh;
using internal::RawNode;

// Gmsh's linear volume elements, which share their node order with core::Cell.
bool isLinearVolumeType(long type) { return type == 4 || type == 5 || type == 6 || type == 7; }

struct ElementType {
  long type;
  int num_nodes;
  int dimension;
  const char* name;
};

// The element types of the Gmsh reference manual. Needed to know how many node numbers follow
// (4.1 lines carry no count) and whether an element is a volume element.
constexpr ElementType kElementTypes[] = {
    {1, 2, 1, "2-node line"},
    {2, 3, 2, "3-node triangle"},
    {3, 4, 2, "4-node quadrangle"},
    {4, 4, 3, "4-node tetrahedron"},
    {5, 8, 3, "8-node hexahedron"},
    {6, 6, 3, "6-node prism"},
    {7, 5, 3, "5-node pyramid"},
    {8, 3, 1, "3-node second order line"},
    {9, 6, 2, "6-node second order triangle"},
    {10, 9, 2, "9-node second order quadrangle"},
    {11, 10, 3, "10-node second order tetrahedron"},
    {12, 27, 3, "27-node second order hexahedron"},
    {13, 18, 3, "18-node second order prism"},
    {14, 14, 3, "14-node second order pyramid"},
    {15, 1, 0, "1-node point"},
    {16, 8, 2, "8-node second order quadrangle"},
    {17, 20, 3, "20-node second order hexahedron"},
    {18, 15, 3, "15-node second order prism"},
    {19, 13, 3, "13-node second order pyramid"},
    {20, 9, 2, "9-node third order incomplete triangle"},
    {21, 10, 2, "10-node third order triangle"},
    {22, 12, 2, "12-node fourth order incomplete triangle"},
    {23, 15, 2, "15-node fourth order triangle"},
    {24, 15, 2, "15-node fifth order incomplete triangle"},
    {25, 21, 2, "21-node fifth order triangle"},
    {26, 4, 1, "4-node third order line"},
    {27, 5, 1, "5-node fourth order line"},
    {28, 6, 1, "6-node fifth order line"},
    {29, 20, 3, "20-node third order tetrahedron"},
    {30, 35, 3, "35-node fourth order tetrahedron"},
    {31, 56, 3, "56-node fifth order tetrahedron"},
    {92, 64, 3, "64-node third order hexahedron"},
    {93, 125, 3, "125-node fourth order hexahedron"},
};

const ElementType* findElementType(long type) {
  for (const ElementType& element_type : kElementTypes) {
    if (element_type.type == type) return &element_type;
  }
  return nullptr;
}

// A $Name ... $EndName section, remembered for messages about where it started.
struct Section {
  std::string name;
  long line;
  std::string endName() const { return "$End" + name.substr(1); }
};

class GmshParser {
 public:
  explicit GmshParser(const std::string& path) : in_(path) { setPaths(path); }
  GmshParser(const std::string& name, std::istream& stream) : in_(name, stream) { setPaths(name); }

  RawMesh parse() {
    if (!in_.next()) throw MeshError(in_.path() + ": the file is empty (expected $MeshFormat)");
    if (in_.token(0) != "$MeshFormat") {
      in_.fail("not a Gmsh mesh file: expected $MeshFormat but found '" +
               std::string(in_.token(0)) + "'");
    }
    readFormat(Section{"$MeshFormat", in_.lineNumber()});

    bool have_nodes = false;
    bool have_elements = false;
    while (in_.next()) {
      const std::string name(in_.token(0));
      if (name.size() < 2 || name[0] != '$') {
        in_.fail("expected a section such as $Nodes or $Elements but found '" + name + "'");
      }
      in_.expectCount(1, "a section name");
      const Section section{name, in_.lineNumber()};
      if (name == "$Nodes") {
        if (have_nodes) in_.fail("second $Nodes section; only one is supported");
        have_nodes = true;
        if (version_ == Version::k22) {
          readNodes22(section);
        } else {
          readNodes41(section);
        }
      } else if (name == "$Elements") {
        if (have_elements) in_.fail("second $Elements section; only one is supported");
        have_elements = true;
        if (version_ == Version::k22) {
          readElements22(section);
        } else {
          readElements41(section);
        }
      } else if (name == "$MeshFormat") {
        in_.fail("second $MeshFormat section");
      } else if (name.rfind("$End", 0) == 0) {
        in_.fail("'" + name + "' without a matching opening section");
      } else {
        skipSection(section);
      }
    }
    if (!have_nodes) fail("the file ends without a $Nodes section");
    if (!have_elements) fail("the file ends without an $Elements section");
    return std::move(raw_);
  }

 private:
  enum class Version { k22, k41 };

  void setPaths(const std::string& path) {
    raw_.node_path = path;
    raw_.element_path = path;
  }

  [[noreturn]] void fail(const std::string& message) const { in_.fail(message); }

  // Moves to the next line of `section`, which must hold an entry and not end the section.
  void nextEntry(const Section& section, const std::string& expecting) {
    if (!in_.next()) {
      fail("the file ends inside the " + section.name + " section (opened on line " +
           std::to_string(section.line) + ") while expecting " + expecting);
    }
    if (in_.token(0)[0] == '$') {
      fail("found '" + std::string(in_.token(0)) + "' while expecting " + expecting + ": the " +
           section.name + " section is shorter than its header says");
    }
  }

  // The line after the last entry must close the section; anything else means the counts in the
  // header do not match what follows.
  void expectEnd(const Section& section, const std::string& announced) {
    const std::string end = section.endName();
    if (!in_.next()) {
      fail("the file ends inside the " + section.name + " section (opened on line " +
           std::to_string(section.line) + ") while expecting " + end);
    }
    if (in_.size() != 1 || in_.token(0) != end) {
      fail("expected " + end + " after " + announced + " but found '" + std::string(in_.token(0)) +
           "'");
    }
  }

  static std::string announced(long count, const std::string& what, long header_line) {
    return "the " + std::to_string(count) + " " + what + " announced on line " +
           std::to_string(header_line);
  }

  void skipSection(const Section& section) {
    const std::string end = section.endName();
    while (in_.next()) {
      if (in_.token(0) == end) return;
    }
    fail("the file ends inside the " + section.name + " section (opened on line " +
         std::to_string(section.line) + ") without " + end);
  }

  void readFormat(const Section& section) {
    nextEntry(section, "the format line 'version file-type data-size'");
    in_.expectCount(3, "version, file type, data size");
    const std::string version(in_.token(0));
    if (version == "2.2") {
      version_ = Version::k22;
    } else if (version == "4.1") {
      version_ = Version::k41;
    } else {
      fail("unsupported Gmsh format version " + version +
           " (only ASCII 2.2 and 4.1 are supported; export with -format msh22 or msh41)");
    }
    const long file_type = in_.integer(1, "file type");
    if (file_type == 1) {
      fail("binary .msh files are not supported; save the mesh as ASCII (Mesh.Binary = 0)");
    }
    if (file_type != 0) fail("unknown file type " + std::to_string(file_type) + " (0 is ASCII)");
    in_.integer(2, "data size");
    expectEnd(section, "the format line");
  }

  void readNodes22(const Section& section) {
    nextEntry(section, "the number of nodes");
    in_.expectCount(1, "number of nodes");
    const long count = in_.nonNegative(0, "number of nodes");
    const long header_line = in_.lineNumber();
    for (long i = 0; i < count; ++i) {
      nextEntry(section, "node " + std::to_string(i + 1) + " of " + std::to_string(count));
      in_.setContext("node " + std::string(in_.token(0)));
      in_.expectCount(4, "node number, x, y, z");
      RawNode node;
      node.number = in_.integer(0, "node number");
      node.position = {in_.real(1, "x coordinate"), in_.real(2, "y coordinate"),
                       in_.real(3, "z coordinate")};
      node.line = node.position_line = in_.lineNumber();
      raw_.nodes.push_back(node);
    }
    expectEnd(section, announced(count, "nodes", header_line));
  }

  // What the header of a 4.1 $Nodes or $Elements section announces.
  struct BlockedHeader {
    long num_blocks = 0;
    long count = 0;  // of nodes or elements in all blocks
    long line = 0;
  };

  // The header line of a 4.1 section of `things` ("node" or "element"): numEntityBlocks, the
  // count, and the smallest and largest tag (read, not used).
  BlockedHeader readBlockedHeader(const Section& section, const std::string& thing) {
    const std::string name = char(std::toupper(thing[0])) + thing.substr(1);  // "Node"
    nextEntry(section, "the " + section.name + " header 'numEntityBlocks num" + name + "s min" +
                           name + "Tag max" + name + "Tag'");
    in_.expectCount(4, "numEntityBlocks, num" + name + "s, min" + name + "Tag, max" + name + "Tag");
    BlockedHeader header;
    header.num_blocks = in_.nonNegative(0, "number of entity blocks");
    header.count = in_.nonNegative(1, "number of " + thing + "s");
    in_.integer(2, "minimum " + thing + " tag");
    in_.integer(3, "maximum " + thing + " tag");
    header.line = in_.lineNumber();
    return header;
  }

  // Throws unless a block of `in_block` more things fits in what the header announced.
  void expectRoomForBlock(const BlockedHeader& header, long read, long in_block,
                          const std::string& thing) const {
    if (in_block > header.count - read) {
      fail("the " + thing + " blocks hold more than the " + std::to_string(header.count) + " " +
           thing + "s announced on line " + std::to_string(header.line));
    }
  }

  // Throws unless the blocks held what the header announced and the section ends there.
  void expectBlocksComplete(const Section& section, const BlockedHeader& header, long read,
                            const std::string& thing) {
    if (read != header.count) {
      fail("the " + thing + " blocks hold " + std::to_string(read) + " " + thing +
           "s but the header on line " + std::to_string(header.line) + " announces " +
           std::to_string(header.count));
    }
    expectEnd(section, announced(header.num_blocks, thing + " blocks", header.line));
  }

  void readNodes41(const Section& section) {
    const BlockedHeader header = readBlockedHeader(section, "node");
    long read = 0;
    for (long b = 0; b < header.num_blocks; ++b) {
      nextEntry(section,
                "node block " + std::to_string(b + 1) + " of " + std::to_string(header.num_blocks));
      in_.expectCount(4, "entityDim, entityTag, parametric, numNodesInBlock");
      const long dimension = in_.nonNegative(0, "entity dimension");
      in_.integer(1, "entity tag");
      const long parametric = in_.nonNegative(2, "parametric flag");
      const long in_block = in_.nonNegative(3, "number of nodes in the block");
      if (dimension > 3) {
        fail("entity dimension must be 0 to 3, found " + std::to_string(dimension));
      }
      if (parametric > 1) {
        fail("parametric flag must be 0 or 1, found " + std::to_string(parametric));
      }
      expectRoomForBlock(header, read, in_block, "node");
      // All tags of the block come first, then all coordinates in the same order.
      const std::size_t first = raw_.nodes.size();
      for (long i = 0; i < in_block; ++i) {
        nextEntry(section, "node tag " + std::to_string(i + 1) + " of " + std::to_string(in_block) +
                               " in the block");
        in_.expectCount(1, "node tag");
        RawNode node;
        node.number = in_.integer(0, "node tag");
        node.line = in_.lineNumber();
        raw_.nodes.push_back(node);
      }
      const std::size_t num_values = 3 + (parametric == 1 ? dimension : 0);
      for (long i = 0; i < in_block; ++i) {
        RawNode& node = raw_.nodes[first + i];
        nextEntry(section, "the coordinates of node " + std::to_string(node.number));
        in_.setContext("node " + std::to_string(node.number));
        in_.expectCount(num_values,
                        parametric == 1 ? "x, y, z and parametric coordinates" : "x, y, z");
        node.position = {in_.real(0, "x coordinate"), in_.real(1, "y coordinate"),
                         in_.real(2, "z coordinate")};
        node.position_line = in_.lineNumber();
      }
      read += in_block;
    }
    expectBlocksComplete(section, header, read, "node");
  }

  // Keeps linear volume elements, counts lower-dimensional ones, throws for other volume
  // elements. Returns whether the element is one whose nodes the caller should read.
  bool acceptElement(long number, const ElementType& type) {
    if (type.dimension < 3) {
      ++raw_.skipped_elements;
      return false;
    }
    if (!isLinearVolumeType(type.type)) {
      throw MeshError(located(in_.path(), in_.lineNumber(),
                              "element " + std::to_string(number) + " has type " +
                                  std::to_string(type.type) + " (" + type.name +
                                  "), which is not supported yet (linear volume elements are: "
                                  "4-node tetrahedra, type 4; 8-node hexahedra, 5; 6-node "
                                  "prisms, 6; 5-node pyramids, 7)"));
    }
    return true;
  }

  const ElementType& knownType(long type) const {
    const ElementType* element_type = findElementType(type);
    if (element_type == nullptr) fail("unknown element type " + std::to_string(type));
    return *element_type;
  }

  void readElements22(const Section& section) {
    raw_.element_section_line = section.line;
    nextEntry(section, "the number of elements");
    in_.expectCount(1, "number of elements");
    const long count = in_.nonNegative(0, "number of elements");
    const long header_line = in_.lineNumber();
    for (long i = 0; i < count; ++i) {
      nextEntry(section, "element " + std::to_string(i + 1) + " of " + std::to_string(count));
      in_.setContext("element " + std::string(in_.token(0)));
      if (in_.size() < 3) {
        fail("expected at least 3 values (element number, type, number of tags) but found " +
             std::to_string(in_.size()));
      }
      const long number = in_.integer(0, "element number");
      const ElementType& type = knownType(in_.integer(1, "element type"));
      const long num_tags = in_.nonNegative(2, "number of tags");
      // Unsigned sum: a corrupt huge tag count must not overflow.
      in_.expectCount(std::size_t{3} + type.num_nodes + static_cast<std::size_t>(num_tags),
                      "element number, type, number of tags, " + std::to_string(num_tags) +
                          (num_tags == 1 ? " tag" : " tags") + " and the " +
                          std::to_string(type.num_nodes) + " nodes of a " + type.name);
      if (!acceptElement(number, type)) continue;
      RawElement element;
      element.number = number;
      element.size = type.num_nodes;
      element.line = in_.lineNumber();
      for (int k = 0; k < element.size; ++k) {
        element.nodes[k] = in_.integer(3 + num_tags + k, "node number");
      }
      raw_.elements.push_back(element);
    }
    expectEnd(section, announced(count, "elements", header_line));
  }

  void readElements41(const Section& section) {
    raw_.element_section_line = section.line;
    const BlockedHeader header = readBlockedHeader(section, "element");
    long read = 0;
    for (long b = 0; b < header.num_blocks; ++b) {
      nextEntry(section, "element block " + std::to_string(b + 1) + " of " +
                             std::to_string(header.num_blocks));
      in_.expectCount(4, "entityDim, entityTag, elementType, numElementsInBlock");
      in_.nonNegative(0, "entity dimension");
      in_.integer(1, "entity tag");
      const ElementType& type = knownType(in_.integer(2, "element type"));
      const long in_block = in_.nonNegative(3, "number of elements in the block");
      expectRoomForBlock(header, read, in_block, "element");
      for (long i = 0; i < in_block; ++i) {
        nextEntry(section, "element " + std::to_string(i + 1) + " of " + std::to_string(in_block) +
                               " in the block");
        in_.setContext("element " + std::string(in_.token(0)));
        in_.expectCount(
            1 + type.num_nodes,
            "element tag and the " + std::to_string(type.num_nodes) + " nodes of a " + type.name);
        const long number = in_.integer(0, "element tag");
        if (!acceptElement(number, type)) continue;
        RawElement element;
        element.number = number;
        element.size = type.num_nodes;
        element.line = in_.lineNumber();
        for (int k = 0; k < element.size; ++k) element.nodes[k] = in_.integer(1 + k, "node number");
        raw_.elements.push_back(element);
      }
      read += in_block;
    }
    expectBlocksComplete(section, header, read, "element");
  }

  LineReader in_;
  RawMesh raw_;
  Version version_ = Version::k22;
};

}  // namespace

MeshReadResult readGmsh(const std::string& path) {
  return internal::finalizeMesh(GmshParser(path).parse());
}

MeshReadResult readGmsh(std::istream& stream, const std::string& name) {
  return internal::finalizeMesh(GmshParser(name, stream).parse());
}

}  // namespace deformable_sim::io
