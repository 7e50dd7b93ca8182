#pragma once
// Where the viewer finds its run-time files (the GLSL shaders) and puts the user's files
// (the last state, F12's screenshots).
#include <string>
#include <vector>

#include "result.h"

namespace viz {

/// Directory holding the running executable, resolved through /proc/self/exe so it does
/// not depend on the working directory. Empty if /proc is unavailable.
std::string executable_dir();

/// Candidate shader directories in search order: EXE_DIR/../../shaders (the build tree,
/// build/bin -> source shaders/), EXE_DIR/../share/accelviz/shaders (an install), then the
/// compile-time ACCEL_SHADER_DIR (the source tree this binary was built from).
std::vector<std::string> shader_dir_candidates();

/// The first candidate that holds every file in `required`. Error: one line naming the
/// first missing file and every directory searched.
accel::Result<std::string> find_shader_dir(const std::vector<std::string>& required);

/// Where the viewer keeps the state it had when its window closed, for --restore without a
/// file: $XDG_STATE_HOME/accelviz/last.state, else ~/.local/state/accelviz/last.state
/// (empty when neither variable is set).
std::string last_state_path();

/// Where F12 writes its numbered screenshots: $XDG_PICTURES_DIR/accelviz when that variable
/// is set (an absolute path), else ~/Pictures/accelviz when ~/Pictures exists, else
/// ./accelviz-pictures -- never the working directory itself, which is the repository's
/// root when the viewer is run from there. Not created here.
std::string pictures_dir();

}  // namespace viz
