#pragma once
// Where a file the user names (a scene, a rays file, a playlist, a script, a bench result)
// comes from when it is not there yet. Natively nothing happens: the reader opens the path
// and says "PATH: cannot open ..." itself. The web page installs a fetcher (browser_web.cpp)
// that copies a missing relative path from the served folder into the page's file system
// at the moment the reader asks for it, so a playlist, a script or a scene can name any file
// next to the page, however deep the reference goes, and no list of them is kept anywhere.
#include <functional>
#include <string>

#include "result.h"

namespace accel {

/// Makes `path` exist, or returns why it cannot (one line naming the path). Called only
/// for a path that does not exist.
using InputFetcher = std::function<Status(const std::string& path)>;

/// Installs the fetcher (the web page's; empty: none). Not thread-safe: set it once, at start.
void set_input_fetcher(InputFetcher fetcher);

/// Before a reader opens `path`: when it does not exist and a fetcher is installed, the
/// fetcher's answer (its error is the reader's error), or a refusal without asking it for an
/// absolute path or one whose `..` leads out of the working directory; otherwise success,
/// and the reader reports a missing file as it always does.
Status fetch_missing_input(const std::string& path);

/// A user-named text file (a playlist, a script, a bench result) read whole, after
/// fetch_missing_input: that error, or "PATH: cannot read WHAT" when the file cannot be
/// opened or read.
Result<std::string> read_input_file(const std::string& path, const std::string& what);

}  // namespace accel
