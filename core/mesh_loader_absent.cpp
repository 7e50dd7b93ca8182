// load_mesh() where the build has no Assimp (the web page): the formats are still known by
// their extension, so a dropped .ply or .glb gets one line saying what to use instead
// rather than the OBJ parser's complaint about its first bytes.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene.h"

namespace accel {

bool is_mesh_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

Result<Scene> load_mesh(const std::string& path) {
  return make_error(path + ": PLY, STL and glTF files need Assimp, which this build does not have; "
                           "convert the mesh to OBJ");
}

}  // namespace accel
