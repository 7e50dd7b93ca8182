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
#include <sstream>
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

/// The PLY header, checked before Assimp sees the file: the format line, elements with
/// their counts, typed properties, `end_header`. Assimp 5.2's PLY reader loops forever on
/// some malformed headers (a property of an unknown type, found by tests/fuzz's fuzz_mesh),
/// so nothing it does not define gets through. A header that claims more elements than the
/// file can hold is rejected here too, before Assimp reserves memory for them (a 100-byte
/// file claiming 10^12 vertices must not be an out-of-memory kill): each vertex needs at
/// least 3 bytes (ASCII "0 0 0" minus spacing is already more; binary floats are 12), each
/// face at least 4.
/// True when the file begins with a PLY signature ("ply" and a line end).
bool starts_like_ply(const std::string& path) {
  char head[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  return in.gcount() == 4 && head[0] == 'p' && head[1] == 'l' && head[2] == 'y' && (head[3] == '\n' || head[3] == '\r');
}

Status check_ply_header(const std::string& path, uintmax_t file_size) {
  static const char* const kTypes[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                       "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  const auto is_type = [](const std::string& t, bool integral_only) {
    for (const char* k : kTypes)
      if (t == k) return !integral_only || (t.find("float") == std::string::npos && t != "double");
    return false;
  };
  const auto fail = [&](int line, const std::string& what) {
    return make_error(path + ":" + std::to_string(line) + ": PLY header: " + what);
  };
  std::ifstream in(path, std::ios::binary);
  std::string line;
  uintmax_t vertices = 0, faces = 0;
  bool in_element = false;
  for (int n = 1; n <= 1000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (n == 1) {
      if (line != "ply") return fail(n, "the first line must be 'ply'");
      continue;
    }
    if (n == 2) {
      if (line != "format ascii 1.0" && line != "format binary_little_endian 1.0" &&
          line != "format binary_big_endian 1.0")
        return fail(n, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      continue;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      const uintmax_t budget = file_size + 1;
      if (vertices > budget / 3 || faces > budget / 4)
        return make_error(path + ": the PLY header declares " + std::to_string(vertices) + " vertices and " +
                          std::to_string(faces) + " faces, more than a file of " + std::to_string(file_size) +
                          " bytes can hold");
      return {};
    }
    std::string a, b, c, extra;
    if (keyword == "element") {
      if (!(words >> a >> b) || (words >> extra) || b.find_first_not_of("0123456789") != std::string::npos ||
          b.size() > 19)
        return fail(n, "expected 'element NAME COUNT'");
      const uintmax_t count = std::stoull(b);
      if (a == "vertex") vertices = count;
      else if (a == "face") faces = count;
      in_element = true;
      continue;
    }
    if (keyword == "property") {
      if (!in_element) return fail(n, "a property before the first element");
      if (!(words >> a)) return fail(n, "expected 'property TYPE NAME'");
      if (a == "list") {
        if (!(words >> a >> b >> c) || (words >> extra) || !is_type(a, true) || !is_type(b, true))
          return fail(n, "expected 'property list COUNT_TYPE INDEX_TYPE NAME' with integer types");
      } else if (!(words >> b) || (words >> extra) || !is_type(a, false)) {
        return fail(n, "expected 'property TYPE NAME' with TYPE one of char, uchar, short, ushort, int, uint, "
                       "float, double (or int8 ... float64)");
      }
      continue;
    }
    std::string shown = line.substr(0, 40);
    for (char& ch : shown)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '?';  // one printable line
    return fail(n, "unexpected line '" + shown + "'");
  }
  return make_error(path + ": PLY header: no 'end_header' line within the first 1000 lines");
}

/// True when the file begins with the binary glTF magic "glTF".
bool starts_like_glb(const std::string& path) {
  char head[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  return in.gcount() == 4 && std::string(head, 4) == "glTF";
}

/// The binary glTF container, checked before Assimp sees the file. Assimp 5.2 allocates
/// what the header and chunk lengths claim before it reads them, so a 600-byte file whose
/// JSON chunk claims 1.8 GB asked for 1.8 GB (fuzz_mesh found it): every length must fit in
/// the file. Version 1 (KHR_binary_glTF) has one content length, version 2 a chunk list.
Status check_glb_container(const std::string& path, uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  const auto word = [&](uint32_t& out) {
    unsigned char b[4] = {};
    in.read(reinterpret_cast<char*>(b), 4);
    out = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;  // little endian
    return in.gcount() == 4;
  };
  const auto fail = [&](const std::string& what) { return make_error(path + ": GLB header: " + what); };
  uint32_t magic = 0, version = 0, length = 0;
  if (!word(magic) || !word(version) || !word(length)) return fail("shorter than its 12-byte header");
  const std::string file_bytes = "the file has " + std::to_string(file_size) + " bytes";
  if (length > file_size) return fail("declares " + std::to_string(length) + " bytes but " + file_bytes);
  if (version == 1) {
    uint32_t content_length = 0, content_format = 0;
    if (!word(content_length) || !word(content_format)) return fail("shorter than its 20-byte version 1 header");
    if (length < 20 || content_length > length - 20)
      return fail("the content declares " + std::to_string(content_length) + " bytes but " + file_bytes);
    return {};
  }
  if (version != 2) return fail("version " + std::to_string(version) + " (1 or 2 expected)");
  uint64_t offset = 12;
  for (int chunk = 0; offset + 8 <= length; ++chunk) {
    uint32_t chunk_length = 0, chunk_type = 0;
    if (!word(chunk_length) || !word(chunk_type)) break;
    if (chunk_length > length - offset - 8)
      return fail("chunk " + std::to_string(chunk) + " declares " + std::to_string(chunk_length) + " bytes but " +
                  file_bytes);
    offset += 8 + uint64_t(chunk_length);
    in.seekg(static_cast<std::streamoff>(offset));
  }
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
  // Assimp reads a file its extension's importer rejects with whichever importer recognises
  // the content, so a PLY named .glb reaches the PLY reader too (fuzz_mesh found one that
  // hung): the header checks go by the content as well as by the name.
  if (extension_of(path) == ".ply" || starts_like_ply(path))
    if (Status st = check_ply_header(path, size); !st) return st.error();
  if (starts_like_glb(path))
    if (Status st = check_glb_container(path, size); !st) return st.error();

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
