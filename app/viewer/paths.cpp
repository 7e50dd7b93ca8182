#include "paths.h"

#include <cstdlib>

#include <filesystem>
#include <system_error>

namespace viz {

namespace fs = std::filesystem;

std::string executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return exe.parent_path().string();
}

std::vector<std::string> shader_dir_candidates() {
  std::vector<std::string> dirs;
  const std::string exe_dir = executable_dir();
  if (!exe_dir.empty()) {
    dirs.push_back((fs::path(exe_dir) / ".." / ".." / "shaders").lexically_normal().string());
    dirs.push_back(
        (fs::path(exe_dir) / ".." / "share" / "accelviz" / "shaders").lexically_normal().string());
  }
#ifdef ACCEL_SHADER_DIR
  dirs.push_back(fs::path(ACCEL_SHADER_DIR).lexically_normal().string());
#endif
  return dirs;
}

accel::Result<std::string> find_shader_dir(const std::vector<std::string>& required) {
  const std::vector<std::string> dirs = shader_dir_candidates();
  // Reported file: the first one missing from the first candidate, the preferred location.
  std::string first_missing;
  for (const std::string& dir : dirs) {
    bool complete = true;
    for (const std::string& file : required) {
      std::error_code ec;
      if (!fs::is_regular_file(fs::path(dir) / file, ec)) {
        if (first_missing.empty()) first_missing = file;
        complete = false;
        break;
      }
    }
    if (complete) return dir;
  }
  if (first_missing.empty() && !required.empty()) first_missing = required.front();
  std::string searched;
  for (const std::string& dir : dirs) searched += (searched.empty() ? "" : ", ") + dir;
  return accel::make_error("shader '" + first_missing + "' not found; searched: " +
                           (searched.empty() ? std::string("(no candidate directories)") : searched));
}

std::string last_state_path() {
  const char* xdg = std::getenv("XDG_STATE_HOME");
  if (xdg && xdg[0] == '/') return std::string(xdg) + "/accelviz/last.state";
  const char* home = std::getenv("HOME");
  if (home && home[0] != '\0') return std::string(home) + "/.local/state/accelviz/last.state";
  return "";
}

std::string pictures_dir() {
  // XDG user directories (xdg-user-dirs): relative values are to be ignored, as for
  // XDG_STATE_HOME above.
  const char* xdg = std::getenv("XDG_PICTURES_DIR");
  if (xdg && xdg[0] == '/') return (fs::path(xdg) / "accelviz").string();
  const char* home = std::getenv("HOME");
  std::error_code ec;
  if (home && home[0] != '\0' && fs::is_directory(fs::path(home) / "Pictures", ec))
    return (fs::path(home) / "Pictures" / "accelviz").string();
  return "accelviz-pictures";
}

}  // namespace viz
