// The viewer's state as a script of the commands that rebuild it (scene, structure, kernel,
// camera, ray, step): `--restore` reopens it. A student's loop is edit, rebuild, look at the
// same ray again; `accelviz-cli check` writes such a file for every wrong ray it reports.
#include <filesystem>

#include "app.h"
#include "rays_io.h"

namespace viz {

std::string App::state_script() const {
  using accel::format_ray_number;
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
  if (!mode_2d()) {
    out += "camera";
    for (float v : {cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x, cam.target.y, cam.target.z, cam.fovy_deg}) {
      out += ' ';
      out += format_ray_number(v);
    }
    out += "\n";
  }
  if (request.build_call_limit) {
    // A failed build's replay: reopened as one (its structure line then builds only as far);
    // there is no structure to trace a ray through.
    out += "construct-until " + std::to_string(request.build_call_limit) + "\n";
    return out;
  }
  const DebugRay& ray = ray_.ray();
  if (ray.active && !mode_2d()) {
    out += "ray " + accel::format_ray_line(ray.ray) + "\n";
    if (ray.player.step() > 0) out += "step " + std::to_string(ray.player.step()) + "\n";
  }
  return out;
}

accel::Status App::save_state(const std::string& path) const {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  return accel::write_file_atomic(path, state_script());  // never half written
}

}  // namespace viz
