// The viewer's state as a script of the commands that rebuild it (scene, structure, kernel,
// camera, ray, step): `--restore` reopens it. A student's loop is edit, rebuild, look at the
// same ray again; `accelviz-cli check` writes such a file for every wrong ray it reports.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app.h"
#include "paths.h"

namespace viz {
namespace {

std::string hex(float v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%a", static_cast<double>(v));
  return buf;
}

}  // namespace

std::string App::state_script() const {
  std::string out = "# accelviz state (reopen: accelviz --restore FILE)\n";
  const std::string& spec = session_.scene_info().spec;
  const bool file_scene = !spec.empty() && spec.rfind("procedural:", 0) != 0;
  if (mode_2d()) {
    out += "# the blackboard's triangles are not part of the state: save them with its Save button\n";
    out += "mode 2d\n";
  } else if (!spec.empty()) {
    std::error_code ec;
    out += "scene " + (file_scene ? std::filesystem::absolute(spec, ec).native() : spec) + "\n";
  }
  const StructureRequest request = session_.current_request();
  out += "structure " + request.name;
  for (const std::string& p : request.params) out += " " + p;
  out += "\n";
  if (request.kernel != accel::Kernel::Watertight && !mode_2d())
    out += "kernel " + std::string(accel::kernel_name(request.kernel)) + "\n";
  const accel::PinholeCamera cam = camera_.pinhole();
  if (!mode_2d())
    out += "camera " + hex(cam.eye.x) + " " + hex(cam.eye.y) + " " + hex(cam.eye.z) + " " + hex(cam.target.x) + " " +
           hex(cam.target.y) + " " + hex(cam.target.z) + " " + hex(cam.fovy_deg) + "\n";
  const DebugRay& ray = ray_.ray();
  if (ray.active && !mode_2d()) {
    const accel::Ray& r = ray.ray;
    out += "ray " + hex(r.org.x) + " " + hex(r.org.y) + " " + hex(r.org.z) + " " + hex(r.dir.x) + " " + hex(r.dir.y) +
           " " + hex(r.dir.z) + " " + hex(r.tmin) + " " + hex(r.tmax) + "\n";
    if (ray.player.step() > 0) out += "step " + std::to_string(ray.player.step()) + "\n";
  }
  return out;
}

accel::Status App::save_state(const std::string& path) const {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp);
    out << state_script();
    if (!out.flush()) return accel::make_error(path + ": cannot write the viewer's state");
  }
  std::filesystem::rename(temp, path, ec);  // never half written
  if (ec) return accel::make_error(path + ": " + ec.message());
  return {};
}

}  // namespace viz
