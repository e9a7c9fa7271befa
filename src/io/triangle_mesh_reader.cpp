#include "deformable_sim/io/triangle_mesh_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <assimp/Importer.hpp>
#include <filesystem>
#include <map>
#include <sstream>

namespace deformable_sim::io {

namespace {

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// Gives every distinct position one index; exact comparison, since an STL writes the very same
// numbers for a vertex each time a triangle uses it.
class VertexMerger {
 public:
  explicit VertexMerger(core::TriangleMesh& mesh) : mesh_(mesh) {}

  int index(const Eigen::Vector3d& position) {
    const auto [entry, inserted] =
        indices_.emplace(std::array<double, 3>{position.x(), position.y(), position.z()},
                         static_cast<int>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(position);
    return entry->second;
  }

 private:
  core::TriangleMesh& mesh_;
  std::map<std::array<double, 3>, int> indices_;
};

// "(nan 0 1)": a corner as the file gives it.
template <typename Vector>
std::string coordinates(const Vector& v) {
  std::ostringstream text;
  text << "(" << v[0] << " " << v[1] << " " << v[2] << ")";
  return text.str();
}

// Appends the triangles of every mesh of `scene` (already in the scene's root frame). Throws
// TriangleMeshError naming `name` for a corner that is not finite; counts in `collapsed` the
// triangles dropped because two of their corners coincide.
void appendTriangles(const aiScene& scene, const Eigen::Vector3d& scale, const std::string& name,
                     core::TriangleMesh& mesh, int& collapsed) {
  VertexMerger merger(mesh);
  // A mirroring scale turns the triangles inside out; swapping two corners turns them back.
  const bool mirrored = scale.prod() < 0.0;
  long number = 0;  // of the triangle in the file, from 1
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& part = *scene.mMeshes[m];
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines have no surface
      ++number;
      Eigen::Vector3i triangle;
      for (int c = 0; c < 3; ++c) {
        const aiVector3D& v = part.mVertices[face.mIndices[c]];
        const Eigen::Vector3d position = scale.cwiseProduct(Eigen::Vector3d(v.x, v.y, v.z));
        if (!position.allFinite()) {
          throw TriangleMeshError(
              "mesh file '" + name + "': corner " + std::to_string(c + 1) + " of triangle " +
              std::to_string(number) + " has a non-finite coordinate " + coordinates(v) +
              (Eigen::Vector3d(v.x, v.y, v.z).allFinite() ? " once scaled by " + coordinates(scale)
                                                          : std::string()));
        }
        triangle[c] = merger.index(position);
      }
      if (mirrored) std::swap(triangle[1], triangle[2]);
      if (triangle[0] == triangle[1] || triangle[1] == triangle[2] || triangle[2] == triangle[0]) {
        ++collapsed;
        continue;
      }
      mesh.triangles.push_back(triangle);
    }
  }
}

// The triangles of what assimp read from `name` (null: it could not).
core::TriangleMesh meshOf(const aiScene* scene, const Assimp::Importer& importer,
                          const std::string& name, const Eigen::Vector3d& scale, int* collapsed) {
  if (!scene) throw TriangleMeshError("mesh file '" + name + "': " + importer.GetErrorString());
  core::TriangleMesh mesh;
  int dropped = 0;
  appendTriangles(*scene, scale, name, mesh, dropped);
  if (collapsed) *collapsed = dropped;
  if (mesh.triangles.empty()) {
    throw TriangleMeshError("mesh file '" + name + "': holds no triangle");
  }
  return mesh;
}

// PreTransformVertices applies the file's node transforms and units (a DAE's <unit>).
constexpr unsigned kSteps =
    aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType;

}  // namespace

std::string resolveMeshUri(const std::string& uri, const PackageResolver& resolver) {
  if (startsWith(uri, "file://")) return uri.substr(7);
  if (startsWith(uri, "package://")) {
    if (!resolver) {
      throw TriangleMeshError("'" + uri +
                              "': package:// needs ROS to find the package; give a file path");
    }
    const std::string path = resolver(uri);
    if (path.empty()) throw TriangleMeshError("'" + uri + "': no such ROS package");
    return path;
  }
  if (uri.find("://") != std::string::npos) {
    throw TriangleMeshError("'" + uri + "': only file://, package:// and plain paths are read");
  }
  return uri;
}

std::string meshResourceUri(const std::string& uri, const std::string& path) {
  if (startsWith(uri, "package://")) return uri;
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  return "file://" + (error ? path : absolute.lexically_normal().string());
}

core::TriangleMesh readTriangleMesh(const std::string& path, const Eigen::Vector3d& scale,
                                    int* collapsed) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw TriangleMeshError("cannot open mesh file '" + path + "': no such file");
  }
  Assimp::Importer importer;
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension.empty() || !importer.IsExtensionSupported(extension)) {
    throw TriangleMeshError("mesh file '" + path + "': unknown format '" + extension +
                            "' (STL, DAE, OBJ and the other formats assimp reads)");
  }
  return meshOf(importer.ReadFile(path, kSteps), importer, path, scale, collapsed);
}

core::TriangleMesh readTriangleMeshFromMemory(const std::string& bytes, const std::string& format,
                                              const std::string& name, const Eigen::Vector3d& scale,
                                              int* collapsed) {
  Assimp::Importer importer;
  if (!importer.IsExtensionSupported("." + format)) {
    throw TriangleMeshError("mesh file '" + name + "': unknown format '" + format + "'");
  }
  if (bytes.empty()) throw TriangleMeshError("mesh file '" + name + "': empty");
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(), kSteps, format.c_str());
  return meshOf(scene, importer, name, scale, collapsed);
}

}  // namespace deformable_sim::io
