// readMesh dispatch plus what both readers share: line reading and number parsing with line
// numbers, and the validation/repair of the raw nodes and tetrahedra (finalizeMesh).
#include "deformable_sim/io/mesh_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "deformable_sim/core/elements/cell.h"
#include "raw_mesh.h"

namespace deformable_sim::io {
namespace internal {
namespace {

// How many numbers a warning lists before it just gives the count.
constexpr std::size_t kListedNumbers = 5;

std::string listNumbers(const std::vector<long>& numbers) {
  std::string text;
  for (std::size_t i = 0; i < numbers.size() && i < kListedNumbers; ++i) {
    if (i > 0) text += ", ";
    text += std::to_string(numbers[i]);
  }
  if (numbers.size() > kListedNumbers) text += ", ...";
  return text;
}

std::string counted(std::size_t count, const std::string& singular, const std::string& plural) {
  return std::to_string(count) + " " + (count == 1 ? singular : plural);
}

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// from_chars rejects a leading '+', which strtod accepts and some writers emit.
std::string_view withoutPlus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

}  // namespace

std::string located(const std::string& path, long line, const std::string& message) {
  return path + ", line " + std::to_string(line) + ": " + message;
}

// --- LineReader ---------------------------------------------------------------------------------

LineReader::LineReader(std::string path, char comment_char)
    : path_(std::move(path)), comment_char_(comment_char), stream_(&file_) {
  std::error_code error;
  // An ifstream happily "opens" a directory and then reads nothing; say what is wrong instead.
  if (std::filesystem::is_directory(path_, error)) {
    throw MeshError("cannot read mesh file '" + path_ + "': it is a directory");
  }
  file_.open(path_);
  if (!file_) {
    throw MeshError("cannot open mesh file '" + path_ + "': " + std::strerror(errno));
  }
}

LineReader::LineReader(std::string path, std::istream& stream, char comment_char)
    : path_(std::move(path)), comment_char_(comment_char), stream_(&stream) {}

bool LineReader::next() {
  while (std::getline(*stream_, line_)) {
    ++line_number_;
    std::string_view rest(line_);
    if (comment_char_ != '\0') rest = rest.substr(0, rest.find(comment_char_));
    tokens_.clear();
    context_.clear();
    // Split on any whitespace; '\r' included so CRLF files read the same.
    static constexpr const char* kSpace = " \t\r\v\f";
    std::size_t begin = rest.find_first_not_of(kSpace);
    while (begin != std::string_view::npos) {
      const std::size_t end = rest.find_first_of(kSpace, begin);
      tokens_.push_back(rest.substr(begin, end == std::string_view::npos ? end : end - begin));
      begin = rest.find_first_not_of(kSpace, end);
    }
    if (!tokens_.empty()) return true;
  }
  if (stream_->bad()) fail("read error");
  tokens_.clear();
  context_.clear();
  return false;
}

void LineReader::expectCount(std::size_t count, const std::string& what) const {
  if (tokens_.size() != count) {
    fail("expected " + counted(count, "value", "values") + " (" + what + ") but found " +
         std::to_string(tokens_.size()));
  }
}

long LineReader::integer(std::size_t i, const std::string& what) const {
  const std::string_view text = withoutPlus(tokens_.at(i));
  long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range) {
    fail(what + " " + quoted(tokens_[i]) + " is out of range");
  }
  if (error != std::errc() || end != text.data() + text.size()) {
    fail("expected an integer " + what + " but found " + quoted(tokens_[i]));
  }
  return value;
}

long LineReader::nonNegative(std::size_t i, const std::string& what) const {
  const long value = integer(i, what);
  if (value < 0) fail(what + " must not be negative, found " + quoted(tokens_[i]));
  return value;
}

double LineReader::real(std::size_t i, const std::string& what) const {
  const std::string_view text = withoutPlus(tokens_.at(i));
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range) {
    fail(what + " " + quoted(tokens_[i]) + " is out of range");
  }
  if (error != std::errc() || end != text.data() + text.size()) {
    fail("expected a number for the " + what + " but found " + quoted(tokens_[i]));
  }
  return value;
}

void LineReader::fail(const std::string& message) const {
  throw MeshError(
      located(path_, line_number_, context_.empty() ? message : context_ + ": " + message));
}

// --- Validation and repair ----------------------------------------------------------------------

namespace {

// Index of each node number in raw.nodes; throws on a non-finite coordinate or a repeated number.
std::unordered_map<long, int> indexNodes(const RawMesh& raw) {
  std::unordered_map<long, int> raw_index_of;
  raw_index_of.reserve(raw.nodes.size());
  for (int i = 0; i < static_cast<int>(raw.nodes.size()); ++i) {
    const RawNode& node = raw.nodes[i];
    if (!node.position.allFinite()) {
      std::ostringstream coordinates;
      coordinates << node.position.x() << " " << node.position.y() << " " << node.position.z();
      throw MeshError(located(raw.node_path, node.position_line,
                              "node " + std::to_string(node.number) +
                                  " has a coordinate that is not a finite number (" +
                                  coordinates.str() + ")"));
    }
    const auto [it, inserted] = raw_index_of.emplace(node.number, i);
    if (!inserted) {
      throw MeshError(located(raw.node_path, node.line,
                              "duplicate node number " + std::to_string(node.number) + " (node " +
                                  std::to_string(node.number) + " was already defined on line " +
                                  std::to_string(raw.nodes[it->second].line) + ")"));
    }
  }
  return raw_index_of;
}

void requireVolumeElements(const RawMesh& raw) {
  if (!raw.elements.empty()) return;
  std::string message = "the mesh has no volume elements";
  if (raw.skipped_elements > 0) {
    message +=
        " (" +
        counted(raw.skipped_elements, "lower-dimensional element", "lower-dimensional elements") +
        " skipped)";
  }
  throw MeshError(located(raw.element_path, raw.element_section_line, message));
}

// Each element's corners as indices into raw.nodes; throws unless every node is known and listed
// once. Marks the nodes some element uses in `used`.
std::vector<std::array<int, 8>> resolveCorners(const RawMesh& raw,
                                               const std::unordered_map<long, int>& raw_index_of,
                                               std::vector<bool>& used) {
  std::vector<std::array<int, 8>> raw_corners(raw.elements.size());
  used.assign(raw.nodes.size(), false);
  for (std::size_t e = 0; e < raw.elements.size(); ++e) {
    const RawElement& element = raw.elements[e];
    const std::string name = "element " + std::to_string(element.number);
    for (int k = 0; k < element.size; ++k) {
      const long number = element.nodes[k];
      const auto it = raw_index_of.find(number);
      if (it == raw_index_of.end()) {
        throw MeshError(located(raw.element_path, element.line,
                                name + " references node " + std::to_string(number) +
                                    ", which is not defined in " + raw.node_path));
      }
      for (int j = 0; j < k; ++j) {
        if (element.nodes[j] == number) {
          throw MeshError(
              located(raw.element_path, element.line,
                      name + " lists node " + std::to_string(number) + " more than once"));
        }
      }
      raw_corners[e][k] = it->second;
      used[it->second] = true;
    }
  }
  return raw_corners;
}

// Copies the used nodes into result.mesh in file order and warns about the dropped ones. Returns
// each raw node's index in the mesh (-1: dropped).
std::vector<int> keepUsedNodes(const RawMesh& raw, const std::vector<bool>& used,
                               MeshReadResult& result) {
  core::Mesh& mesh = result.mesh;
  std::vector<int> new_index(raw.nodes.size(), -1);
  std::vector<long> dropped;
  for (int i = 0; i < static_cast<int>(raw.nodes.size()); ++i) {
    if (!used[i]) {
      dropped.push_back(raw.nodes[i].number);
      continue;
    }
    new_index[i] = mesh.numNodes();
    mesh.positions.push_back(raw.nodes[i].position);
    mesh.node_numbers.push_back(raw.nodes[i].number);
  }
  if (!dropped.empty()) {
    result.warnings.push_back(raw.node_path + ": dropped " +
                              counted(dropped.size(), "node", "nodes") +
                              " that no element uses: " + listNumbers(dropped));
  }
  return new_index;
}

// One raw element with its corners as indices into the finished mesh's nodes.
struct PlacedElement {
  const RawElement& raw;
  std::array<int, 8> corners;
  const std::string& path;
};

double longestEdge(const PlacedElement& element, const core::Mesh& mesh) {
  double longest_edge = 0.0;
  for (int a = 0; a < element.raw.size; ++a) {
    for (int b = a + 1; b < element.raw.size; ++b) {
      longest_edge = std::max(
          longest_edge,
          (mesh.positions[element.corners[a]] - mesh.positions[element.corners[b]]).norm());
    }
  }
  return longest_edge;
}

// "path, line 7: element 3 (nodes 1 2 3 4) <what>"
std::string describe(const PlacedElement& element, const std::string& what) {
  std::ostringstream details;
  details << "element " << element.raw.number << " (nodes";
  for (int k = 0; k < element.raw.size; ++k) details << " " << element.raw.nodes[k];
  details << ") " << what;
  return located(element.path, element.raw.line, details.str());
}

// Appends the tetrahedron to `mesh`, swapping its last two corners when it is mirrored (returns
// true then); throws when its volume overflows or is negligible.
bool addTetrahedron(const PlacedElement& element, double longest_edge, double negligible,
                    core::Mesh& mesh) {
  core::Tetrahedron tet;
  for (int k = 0; k < 4; ++k) tet[k] = element.corners[k];
  const double volume = core::signedVolume(mesh.positions, tet);
  if (!std::isfinite(volume)) {
    std::ostringstream what;
    what << "has a volume that overflows (longest edge " << longest_edge << " m)";
    throw MeshError(describe(element, what.str()));
  }
  if (std::abs(6.0 * volume) <= negligible) {
    std::ostringstream what;
    what << "has zero volume (" << volume << " m^3, longest edge " << longest_edge
         << " m): its corners are coplanar or coincide";
    throw MeshError(describe(element, what.str()));
  }
  const bool mirrored = volume < 0.0;
  if (mirrored) std::swap(tet[2], tet[3]);
  mesh.tetrahedra.push_back(tet);
  return mirrored;
}

// Appends the pyramid, wedge or hexahedron to `mesh`, mirrored when listed in mirrored order
// (returns true then); throws when det J does not stay positive within it.
bool addCell(const PlacedElement& element, double negligible, core::Mesh& mesh) {
  core::Cell cell;
  cell.type = static_cast<core::CellType>(element.raw.size);
  for (int k = 0; k < element.raw.size; ++k) cell.nodes[k] = element.corners[k];
  auto [low, high] = core::jacobianRange(cell.type, core::cellCorners(cell, mesh.positions));
  const bool mirrored = high < -negligible;
  if (mirrored) {
    cell = core::mirrored(cell);
    std::tie(low, high) = core::jacobianRange(cell.type, core::cellCorners(cell, mesh.positions));
  }
  if (!(low > negligible)) {
    std::ostringstream what;
    what << "is degenerate or tangled: det J ranges over [" << low << ", " << high
         << "] m^3 within it (it must stay positive)";
    throw MeshError(describe(element, what.str()));
  }
  mesh.cells.push_back(cell);
  return mirrored;
}

// Adds every element to result.mesh, rejecting degenerate ones and reorienting mirrored ones (one
// warning for all of those). Returns the file's number of each kept tetrahedron.
std::vector<long> addElements(const RawMesh& raw,
                              const std::vector<std::array<int, 8>>& raw_corners,
                              const std::vector<int>& new_index, MeshReadResult& result) {
  core::Mesh& mesh = result.mesh;
  std::vector<long> reoriented;
  std::vector<long> tetrahedron_numbers;
  for (std::size_t e = 0; e < raw.elements.size(); ++e) {
    PlacedElement element{raw.elements[e], {}, raw.element_path};
    for (int k = 0; k < element.raw.size; ++k) element.corners[k] = new_index[raw_corners[e][k]];
    const double longest_edge = longestEdge(element, mesh);
    // Scale-free: 6V (a tetrahedron) or det J (the others) against the cube of the element size.
    const double negligible = 1e-12 * longest_edge * longest_edge * longest_edge;
    const bool is_tetrahedron = element.raw.size == 4;
    const bool mirrored = is_tetrahedron ? addTetrahedron(element, longest_edge, negligible, mesh)
                                         : addCell(element, negligible, mesh);
    if (mirrored) reoriented.push_back(element.raw.number);
    if (is_tetrahedron) tetrahedron_numbers.push_back(element.raw.number);
  }
  if (!reoriented.empty()) {
    result.warnings.push_back(raw.element_path + ": reoriented " +
                              counted(reoriented.size(), "element listed in mirrored order",
                                      "elements listed in mirrored order") +
                              " (tetrahedra: 3rd and 4th node swapped; others: top and bottom "
                              "swapped, a pyramid's base reversed): " +
                              (reoriented.size() == 1 ? "element " : "elements ") +
                              listNumbers(reoriented));
  }
  return tetrahedron_numbers;
}

// Slivers are kept (their volume is positive) but named: they make the stiffness ill-conditioned.
void warnAboutSlivers(const RawMesh& raw, const std::vector<long>& tetrahedron_numbers,
                      MeshReadResult& result) {
  const core::Mesh& mesh = result.mesh;
  const std::vector<int> slivers = core::sliverTetrahedra(mesh);
  if (slivers.empty()) return;
  std::vector<long> numbers;
  int worst = slivers.front();
  for (int e : slivers) {
    numbers.push_back(tetrahedron_numbers[e]);
    if (core::shapeQuality(mesh.positions, mesh.tetrahedra[e]) <
        core::shapeQuality(mesh.positions, mesh.tetrahedra[worst])) {
      worst = e;
    }
  }
  std::ostringstream text;
  text << raw.element_path << ": kept "
       << counted(slivers.size(), "sliver tetrahedron", "sliver tetrahedra")
       << " (shape quality below " << core::kSliverQuality << ", 1 = regular; the worst "
       << core::shapeQuality(mesh.positions, mesh.tetrahedra[worst]) << " at element "
       << tetrahedron_numbers[worst] << "), which make the stiffness ill-conditioned: "
       << (slivers.size() == 1 ? "element " : "elements ") << listNumbers(numbers);
  result.warnings.push_back(text.str());
}

}  // namespace

MeshReadResult finalizeMesh(const RawMesh& raw) {
  const std::unordered_map<long, int> raw_index_of = indexNodes(raw);
  requireVolumeElements(raw);
  std::vector<bool> used;
  const std::vector<std::array<int, 8>> raw_corners = resolveCorners(raw, raw_index_of, used);
  MeshReadResult result;
  const std::vector<int> new_index = keepUsedNodes(raw, used, result);
  const std::vector<long> tetrahedron_numbers = addElements(raw, raw_corners, new_index, result);
  warnAboutSlivers(raw, tetrahedron_numbers, result);
  return result;
}

}  // namespace internal

// --- Dispatch -----------------------------------------------------------------------------------

MeshReadResult readMesh(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw MeshError("cannot read mesh file '" + path + "': it is a directory");
  }
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".msh") return readGmsh(path);
  if (extension.empty() || extension == ".node" || extension == ".ele") return readTetGen(path);
  throw MeshError("cannot read mesh file '" + path + "': unknown extension '" + extension +
                  "' (expected .msh for Gmsh, or .node, .ele or no extension for TetGen)");
}

}  // namespace deformable_sim::io
