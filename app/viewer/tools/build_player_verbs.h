#pragma once
// The construction mode's script verbs (commands.h). GL-free: the catalogue
// (script_verbs.h) reads them without their runs; BuildPlayer::add_verbs() binds them to
// the player.
#include <charconv>
#include <string>
#include <vector>

#include "commands.h"
#include "registry.h"

namespace viz {

struct ConstructUntilArgs {
  size_t calls = 0;  ///< build-log calls
  /// accelviz-cli check's comment lines atop the script (what failed); set by
  /// parse_script().
  std::vector<std::string> header;
};

/// Success, or why there is no construction to show; the error names the command (its
/// message alone would not say which step failed).
template <class Player>
accel::Status need_construction(const Player& player, const char* verb) {
  if (auto st = player.need_trace(); !st) return accel::make_error(std::string(verb) + ": " + st.error().message);
  return {};
}

template <class Verbs>
void build_player_verbs(Verbs& verbs) {
  verbs.template add<NoArgs>("construct", "construct", "record the current structure's build (construction mode)",
                             parse_no_words,
                             [](auto& build, auto& host, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (auto st = host.session().need_structure(); !st) return st;
                               host.construct();  // synchronous in script mode; in the window the
                                                  // playlist waits for it
                               if (!host.synchronous()) return {};
                               return need_construction(build, "construct");
                             });
  verbs.template add<ConstructUntilArgs>(
      "construct-until", "construct-until N",
      "a student's failed build replayed up to the fault (`accelviz-cli check` writes it): record the current "
      "structure's build stopped right after its N-th build-log call and show its last step; the `structure` line "
      "before it builds only as far",
      [](const VerbArgs& a, ConstructUntilArgs& s) -> std::string {
        if (a.size() != 1) return a.usage_error();
        const std::string& w = a[0];
        const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), s.calls);
        if (ec != std::errc() || end != w.data() + w.size() || s.calls == 0)
          return "construct-until: N must be a whole number of build-log calls, at least 1, got '" + w +
                 "' (a build that failed before its first call has nothing to replay)";
        return "";
      },
      [](auto& build, auto& host, const ConstructUntilArgs& s, ScriptHost&) -> accel::Status {
        // No need_structure(): a failed build's replay has none (its structure line's build
        // stopped too); what it needs is a student's structure, whose build log is counted.
        auto& session = host.session();
        const auto request = session.current_request();
        auto info = accel::find_structure(request.name);
        if (!info) return info.error();
        if (!info.value()->student)
          return accel::make_error("construct-until: " + request.name +
                                   " is not a student's structure (only the kit counts build-log calls; use "
                                   "construct)");
        build.construct_until(session.scene_ptr(), request, s.calls, s.header, host.synchronous());
        if (!host.synchronous()) return {};
        return need_construction(build, "construct-until");
      });
  verbs.template add<PlayerMove>(
      "build-step", "build-step N | build-step end | build-step back N | build-step start",
      "move the construction player",
      [](const VerbArgs& a, PlayerMove& s) { return parse_step_words(a, s, /*hit=*/false); },
      [](auto& build, auto& host, const PlayerMove& s, ScriptHost& script) -> accel::Status {
        if (auto st = need_construction(build, "build-step"); !st) return st;
        auto& clock = build.player();
        clock.pause();
        const size_t from = clock.step();
        step_clock(clock, s.mode, static_cast<size_t>(s.count));  // transport_controls.h
        build.set_active(true);
        host.walk_recorded(clock, from, script);
        return {};
      });
  verbs.template add<NoArgs>("print-build-step", "print-build-step", "`build step K/N: TEXT` (K steps applied)",
                             parse_no_words,
                             [](auto& build, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (auto st = need_construction(build, "print-build-step"); !st) return st;
                               print_script_line(build.step_line());
                               return {};
                             });
  verbs.template add<OnOff>("sah-plot", "sah-plot on|off", "the construction panel's SAH cost plot",
                            parse_on_off_word,
                            [](auto& build, auto&, const OnOff& s, ScriptHost&) -> accel::Status {
                              build.set_sah_plot(s.on);
                              return {};
                            });
}

}  // namespace viz
