// load_mesh() where the build has no Assimp (the web page): is_mesh_format() (scene.cpp)
// still knows the formats by their extension, so a dropped .ply or .glb gets one line saying
// what to use instead rather than the OBJ parser's complaint about its first bytes.
#include "scene.h"

namespace accel {

Result<Scene> load_mesh(const std::string& path) {
  return make_error(path + ": PLY, STL and glTF files need Assimp, which this build does not have; "
                           "convert the mesh to OBJ");
}

}  // namespace accel
