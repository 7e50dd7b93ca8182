#include "input_files.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace accel {
namespace {

InputFetcher& fetcher() {
  static InputFetcher installed;
  return installed;
}

}  // namespace

void set_input_fetcher(InputFetcher f) { fetcher() = std::move(f); }

Status fetch_missing_input(const std::string& path) {
  const InputFetcher& f = fetcher();
  if (!f || path.empty()) return {};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return {};
  // What a fetcher may be asked for: a path below the working directory (the page's folder).
  if (path[0] == '/')
    return make_error(path + ": cannot open (an absolute path; the page reads files of its own folder only)");
  const std::string normal = std::filesystem::path(path).lexically_normal().generic_string();
  if (normal == ".." || normal.rfind("../", 0) == 0)
    return make_error(path + ": cannot open (outside the page's folder, which is all the page may read)");
  return f(path);
}

Result<std::string> read_input_file(const std::string& path, const std::string& what) {
  if (Status fetched = fetch_missing_input(path); !fetched) return fetched.error();  // the page: from its folder
  std::ifstream file(path, std::ios::binary);
  if (!file) return make_error(path + ": cannot read " + what);
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return make_error(path + ": cannot read " + what);
  return text.str();
}

}  // namespace accel
