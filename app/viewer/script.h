#pragma once
// The viewer's command scripts (`accelviz --script FILE`): one command per line, `#`
// starts a comment. Parsed here into plain commands, GL-free, so the parser is unit-tested;
// App executes them and main() renders for the screenshot commands. Each verb is one
// registration of its module (commands.h): its name, usage, help, its own typed arguments,
// their parser and its run. script_verbs.h is the catalogue the parser reads (the
// registrations without their runs); `accelviz --list commands` prints it and docs/viewer.md's
// table is that print. Errors are "SCRIPT:LINE: message".
#include <any>
#include <string>
#include <string_view>
#include <vector>

#include "result.h"

namespace viz {

/// One parsed command: its verb and the verb's own arguments, as the verb's parser made
/// them (the registration that declares the verb names their type: HeatmapScale,
/// StructureArgs, ...).
struct ScriptCommand {
  std::string_view verb;  ///< its name as the catalogue spells it ("heatmap-scale")
  int line = 0;           ///< 1-based line in the script
  std::any args;          ///< the verb's arguments

  /// The arguments as the verb's type (std::bad_any_cast for another type: a programming
  /// error).
  template <class Args>
  const Args& get() const {
    return std::any_cast<const Args&>(args);
  }
  template <class Args>
  Args& get() {
    return std::any_cast<Args&>(args);
  }
};

/// Parses `text` (the script named `script_name` in messages). Validates everything that
/// needs no scene or window: command names, argument counts and numbers, structure names
/// and parameters (against the registry, as accelviz-cli does). Error: "SCRIPT:LINE: message".
/// A `structure` line followed by `construct-until N` gets N too (StructureArgs::calls): a
/// failed build's replay builds only as far as the check's build got.
accel::Result<std::vector<ScriptCommand>> parse_script(const std::string& text, const std::string& script_name);

/// Reads and parses a script file. Error names the file when it cannot be read.
accel::Result<std::vector<ScriptCommand>> load_script(const std::string& path);

/// "SCRIPT:LINE: message", the format of every script error.
std::string script_error(const std::string& script_name, int line, const std::string& message);

}  // namespace viz
