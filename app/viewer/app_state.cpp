// The viewer's state as a script of the commands that rebuild it (scene, structure, kernel,
// camera, ray, step): `--restore` reopens it. A student's loop is edit, rebuild, look at the
// same ray again; `accelviz-cli check` writes such a file for every wrong ray it reports.
#include <filesystem>

#include "app.h"
#include "rays_io.h"

namespace viz {

std::string App::state_script() const {
  std::string out = "# accelviz state (reopen: accelviz --restore FILE)\n";
  for (Tool* tool : tool_list_) tool->save_state(out, *this);
  return out;
}

accel::Status App::save_state(const std::string& path) const {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  return accel::write_file_atomic(path, state_script());  // never half written
}

}  // namespace viz
