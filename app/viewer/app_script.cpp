// App, part 3: script dispatch. Each command goes to its verb's run, found by name in the
// table App::App() filled from the registrations (commands.h): App's own verbs
// (global_verbs.h: the window, the camera, the panels, colours, screenshots, the saved
// state) and each tool's add_verbs(). Builds, heat
// maps, comparisons and sweeps run synchronously in script mode, so every command sees the
// result of the previous one; screenshots go through the ScriptHost (main.cpp).
#include "app.h"

namespace viz {

accel::Status App::execute(const ScriptCommand& c, ScriptHost& host) {
  const Verb* verb = verbs_.find(c.verb);
  if (!verb || !verb->run) return accel::make_error("no tool runs this command");  // App::App() checks every verb
  return verb->run(c, host);
}

}  // namespace viz
