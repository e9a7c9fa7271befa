#include "deformable_sim/io/triangle_mesh_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <assimp/Importer.hpp>
#include <filesystem>
#include <map>

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

// Appends the triangles of every mesh of `scene` (already in the scene's root frame).
void appendTriangles(const aiScene& scene, const Eigen::Vector3d& scale, core::TriangleMesh& mesh) {
  VertexMerger merger(mesh);
  // A mirroring scale turns the triangles inside out; swapping two corners turns them back.
  const bool mirrored = scale.prod() < 0.0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& part = *scene.mMeshes[m];
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines have no surface
      Eigen::Vector3i triangle;
      for (int c = 0; c < 3; ++c) {
        const aiVector3D& v = part.mVertices[face.mIndices[c]];
        triangle[c] = merger.index(scale.cwiseProduct(Eigen::Vector3d(v.x, v.y, v.z)));
      }
      if (mirrored) std::swap(triangle[1], triangle[2]);
      if (triangle[0] == triangle[1] || triangle[1] == triangle[2] || triangle[2] == triangle[0]) {
        continue;
      }
      mesh.triangles.push_back(triangle);
    }
  }
}

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

core::TriangleMesh readTriangleMesh(const std::string& path, const Eigen::Vector3d& scale) {
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
  // PreTransformVertices applies the file's node transforms and units (a DAE's <unit>).
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene) {
    throw TriangleMeshError("mesh file '" + path + "': " + importer.GetErrorString());
  }
  core::TriangleMesh mesh;
  appendTriangles(*scene, scale, mesh);
  if (mesh.triangles.empty()) {
    throw TriangleMeshError("mesh file '" + path + "': holds no triangle");
  }
  return mesh;
}

}  // namespace deformable_sim::io
