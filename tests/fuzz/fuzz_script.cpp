// libFuzzer target: the viewer's command scripts (--script) and lecture playlists
// (--playlist), both parsed without a window (app/viewer/script.cpp, playlist.cpp). The
// first byte picks which; every error is one "NAME:LINE: message" line.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "playlist.h"
#include "script.h"

namespace {
void require_one_line(const std::string& message, const std::string& name) {
  if (message.find('\n') != std::string::npos || message.rfind(name, 0) != 0) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1) {
    auto playlist = viz::parse_playlist(text, "fuzz.playlist");
    if (!playlist) require_one_line(playlist.error().message, "fuzz.playlist");
  } else {
    auto script = viz::parse_script(text, "fuzz.script");
    if (!script) require_one_line(script.error().message, "fuzz.script");
  }
  return 0;
}
