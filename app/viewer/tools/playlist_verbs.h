#pragma once
// The lecture playlist's script verbs (commands.h). GL-free: the catalogue (script_verbs.h)
// reads them without their runs; PlaylistTool::add_verbs() binds them to the tool.
#include <string>

#include "commands.h"

namespace viz {

/// `next` / `prev`: the playlist's next or previous state, its commands run now.
template <class Playlist, class Host>
accel::Status move_in_playlist(Playlist& playlist, Host& host, bool forward, ScriptHost& script) {
  if (!playlist.loaded()) return accel::make_error("no playlist loaded (use playlist FILE first)");
  host.go_to_state(forward ? playlist.next_index() : playlist.prev_index());
  host.run_playlist(&script);
  return {};
}

template <class Verbs>
void playlist_verbs(Verbs& verbs) {
  verbs.template add<Word>("playlist", "playlist FILE", "load a lecture playlist (playlist.h), show its first state",
                           parse_one_word,
                           [](auto&, auto& host, const Word& file, ScriptHost& script) -> accel::Status {
                             if (auto st = host.load_playlist(file.word); !st) return st;
                             host.run_playlist(&script);
                             return {};
                           });
  verbs.template add<NoArgs>("next", "next", "the playlist's next state", parse_no_words,
                             [](auto& playlist, auto& host, const NoArgs&, ScriptHost& script) -> accel::Status {
                               return move_in_playlist(playlist, host, true, script);
                             });
  verbs.template add<NoArgs>("prev", "prev", "the playlist's previous state", parse_no_words,
                             [](auto& playlist, auto& host, const NoArgs&, ScriptHost& script) -> accel::Status {
                               return move_in_playlist(playlist, host, false, script);
                             });
  verbs.template add<NoArgs>("print-state", "print-state", "`state K/N: TITLE`", parse_no_words,
                             [](auto& playlist, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (!playlist.loaded()) return accel::make_error("print-state: no playlist loaded");
                               print_script_line(playlist.state_line());
                               return {};
                             });
}

}  // namespace viz
