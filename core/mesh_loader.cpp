// PLY, STL and glTF 2.0 / GLB loading through Assimp (Debian's libassimp-dev). Assimp
// parses; this file decides the numbering (docs/hits.md): meshes in the order the scene's
// node tree reaches them (depth first, children in file order; a file whose nodes hold no
// mesh: the meshes in file order), each mesh's faces in file order, a polygon
// fan-triangulated in place as for OBJ. No Assimp post-processing step runs that would
// reorder, merge or re-triangulate (Triangulate ear-clips, JoinIdenticalVertices reorders);
// only ValidateDataStructure, which rejects out-of-range indices.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scene.h"

namespace accel {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string extension_of(const std::string& path) { return lower(std::filesystem::path(path).extension().string()); }

/// Assimp's message on one line (printable: it may quote the input).
std::string one_line(std::string msg) {
  while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r' || msg.back() == ' ')) msg.pop_back();
  for (char& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  return printable(msg, 300);
}

/// A PLY header that claims more elements than the file can hold is rejected before Assimp
/// reserves memory for them (a 100-byte file claiming 10^12 vertices must not be an
/// out-of-memory kill). Each vertex needs at least 3 bytes (ASCII "0 0 0" minus spacing is
/// already more; binary floats are 12), each face at least 4.
Status check_ply_counts(const std::string& path, uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  uintmax_t vertices = 0, faces = 0;
  for (int n = 0; n < 1000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "end_header") break;
    unsigned long long count = 0;
    char kind[32] = {};
    if (std::sscanf(line.c_str(), "element %31s %llu", kind, &count) == 2) {
      if (std::string(kind) == "vertex") vertices = count;
      else if (std::string(kind) == "face") faces = count;
    }
  }
  const uintmax_t budget = file_size + 1;
  if (vertices > budget / 3 || faces > budget / 4)
    return make_error(path + ": the PLY header declares " + std::to_string(vertices) + " vertices and " +
                      std::to_string(faces) + " faces, more than a file of " + std::to_string(file_size) +
                      " bytes can hold");
  return {};
}

struct Collector {
  const aiScene* scene = nullptr;
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  std::vector<uint8_t> mesh_used;
  std::string error;

  /// Appends mesh `m` with the node's transform `to_world`.
  bool add_mesh(unsigned m, const aiMatrix4x4& to_world, bool identity) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (positions.size() + mesh->mNumVertices > 0xFFFFFFFFull) {
      error = "more than 2^32 vertices";
      return false;
    }
    const uint32_t base = static_cast<uint32_t>(positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      aiVector3D p = mesh->mVertices[v];
      if (!identity) p = to_world * p;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        error = "mesh " + std::to_string(m) + " vertex " + std::to_string(v) + " has a non-finite coordinate";
        return false;
      }
      positions.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines: no triangles (as OBJ's p and l)
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          error = "mesh " + std::to_string(m) + " face " + std::to_string(f) + " has an index out of range";
          return false;
        }
      }
      for (unsigned k = 2; k < face.mNumIndices; ++k)  // fan: (v0,v1,v2), (v0,v2,v3), ...
        triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[k - 1], base + face.mIndices[k]);
    }
    return true;
  }

  bool walk(const aiNode* node, const aiMatrix4x4& parent, int depth) {
    if (depth > 256) {
      error = "the node tree is deeper than 256 levels";
      return false;
    }
    const aiMatrix4x4 to_world = parent * node->mTransformation;
    const bool identity = to_world.IsIdentity();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned m = node->mMeshes[i];
      if (m >= scene->mNumMeshes) {
        error = "a node refers to mesh " + std::to_string(m) + " of " + std::to_string(scene->mNumMeshes);
        return false;
      }
      mesh_used[m] = 1;
      if (!add_mesh(m, to_world, identity)) return false;
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      if (!walk(node->mChildren[c], to_world, depth + 1)) return false;
    return true;
  }
};

}  // namespace

bool is_mesh_format(const std::string& path) {
  const std::string ext = extension_of(path);
  return ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

Result<Scene> load_mesh(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return make_error(path + ": cannot open the file");
  if (std::filesystem::is_directory(status)) return make_error(path + ": is a directory, not a mesh file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path + ": cannot read the file size");
  if (size == 0) return make_error(path + ": the file is empty");
  if (extension_of(path) == ".ply")
    if (Status st = check_ply_counts(path, size); !st) return st.error();

  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  } catch (const std::exception& e) {  // Assimp reports through GetErrorString; a throw is a failed allocation
    return make_error(path + ": " + one_line(e.what()));
  }
  if (!scene) return make_error(path + ": " + one_line(importer.GetErrorString()));
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || scene->mNumMeshes == 0 || !scene->mRootNode)
    return make_error(path + ": no triangles (the file holds no mesh)");

  Collector c;
  c.scene = scene;
  c.mesh_used.assign(scene->mNumMeshes, 0);
  if (!c.walk(scene->mRootNode, aiMatrix4x4(), 0)) return make_error(path + ": " + c.error);
  if (c.triangles.empty() && c.positions.empty()) {
    // No node holds a mesh: take them in file order, untransformed.
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
      if (!c.add_mesh(m, aiMatrix4x4(), true)) return make_error(path + ": " + c.error);
  }
  if (c.triangles.empty()) return make_error(path + ": no triangles (only points or lines)");
  std::string name = std::filesystem::path(path).filename().string();
  return Scene(std::move(c.positions), std::move(c.triangles), name);
}

}  // namespace accel
