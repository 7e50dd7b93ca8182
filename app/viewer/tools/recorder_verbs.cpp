// The recorder's script verb, GL-free half (script_verbs.h). The run half is
// Recorder::script_verbs().
#include <cstdio>

#include "script_verbs.h"
#include "video_writer.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"record", CommandKind::Record, "record PATH.gif|PATH.mp4 [fps=N] [ui=on|off] [size=WxH] | record stop",
     "record one frame per step moved (`step`, `build-step`) until `record stop`, which finishes the file; fps "
     "1..60 (default 4); `ui=off`: the 3D view only",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() == 1 && a[0] == "stop") {
         c.kind = CommandKind::RecordStop;
         return "";
       }
       if (a.size() < 1) return a.usage_error();
       if (auto format = video_format_of(a[0]); !format) return "record: " + format.error().message;
       c.name = a[0];
       c.ints[0] = 4;
       c.on = true;
       for (size_t i = 1; i < a.size(); ++i) {
         const std::string& w = a[i];
         int width = 0, height = 0;
         char x = 0, extra = 0;
         if (w.rfind("fps=", 0) == 0) {
           if (!parse_script_int(w.substr(4), &c.ints[0]) || c.ints[0] < 1 || c.ints[0] > 60)
             return "record: fps must be an integer in 1..60, got '" + w.substr(4) + "'";
         } else if (w.rfind("ui=", 0) == 0) {
           if (!parse_on_off(w.substr(3), &c.on)) return "record: ui must be on or off, got '" + w.substr(3) + "'";
         } else if (w.rfind("size=", 0) == 0) {
           if (std::sscanf(w.c_str() + 5, "%d%c%d%c", &width, &x, &height, &extra) != 3 || (x != 'x' && x != 'X') ||
               width < 16 || height < 16 || width > 8192 || height > 8192)
             return "record: size must be WxH with W and H in 16..8192, got '" + w.substr(5) + "'";
           c.values[0] = static_cast<float>(width);
           c.values[1] = static_cast<float>(height);
         } else {
           return a.usage_error();
         }
       }
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> recorder_verbs() { return kVerbs; }

}  // namespace viz
