#pragma once
// The recorder's script verb (commands.h). GL-free: the catalogue (script_verbs.h) reads it
// without its run; Recorder::add_verbs() binds it to the recorder.
#include <cstdio>
#include <string>

#include "commands.h"
#include "tools/recorder.h"
#include "video_writer.h"

namespace viz {

struct RecordArgs {
  bool stop = false;  ///< `record stop`
  std::string path;
  RecordOptions options;
};

/// `record`'s words: `stop`, or the path and its settings.
inline std::string parse_record_words(const VerbArgs& a, RecordArgs& s) {
  if (a.size() == 1 && a[0] == "stop") {
    s.stop = true;
    return "";
  }
  if (a.size() < 1) return a.usage_error();
  if (auto format = video_format_of(a[0]); !format) return "record: " + format.error().message;
  s.path = a[0];  // fps 4, with the panels, the captured size: RecordOptions' defaults
  for (size_t i = 1; i < a.size(); ++i) {
    const std::string& w = a[i];
    int width = 0, height = 0;
    char x = 0, extra = 0;
    if (w.rfind("fps=", 0) == 0) {
      if (!parse_script_int(w.substr(4), &s.options.fps) || s.options.fps < 1 || s.options.fps > 60)
        return "record: fps must be an integer in 1..60, got '" + w.substr(4) + "'";
    } else if (w.rfind("ui=", 0) == 0) {
      if (!parse_on_off(w.substr(3), &s.options.ui)) return "record: ui must be on or off, got '" + w.substr(3) + "'";
    } else if (w.rfind("size=", 0) == 0) {
      if (std::sscanf(w.c_str() + 5, "%d%c%d%c", &width, &x, &height, &extra) != 3 || (x != 'x' && x != 'X') ||
          width < 16 || height < 16 || width > 8192 || height > 8192)
        return "record: size must be WxH with W and H in 16..8192, got '" + w.substr(5) + "'";
      s.options.width = width;
      s.options.height = height;
    } else {
      return a.usage_error();
    }
  }
  return "";
}

template <class Verbs>
void recorder_verbs(Verbs& verbs) {
  verbs.template add<RecordArgs>(
      "record", "record PATH.gif|PATH.mp4 [fps=N] [ui=on|off] [size=WxH] | record stop",
      "record one frame per step moved (`step`, `build-step`) until `record stop`, which finishes the file; fps "
      "1..60 (default 4); `ui=off`: the 3D view only",
      parse_record_words, [](auto& recorder, auto&, const RecordArgs& s, ScriptHost& script) -> accel::Status {
        if (s.stop) {
          if (auto st = recorder.stop(); !st) return st;
          print_script_line(recorder.notice());  // "wrote PATH (N frames)"
          return {};
        }
        if (auto st = recorder.start(s.path, s.options); !st) return st;
        script.render(1);  // the first frame: the animation as it stands
        if (!recorder.recording()) return accel::make_error("record: " + recorder.notice());
        return {};
      });
}

}  // namespace viz
