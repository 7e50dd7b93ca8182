// The lecture playlist's script verbs, GL-free half (script_verbs.h). The run half is
// PlaylistTool::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"playlist", CommandKind::Playlist, "playlist FILE", "load a lecture playlist (playlist.h), show its first state",
     parse_one_word},
    {"next", CommandKind::Next, "next", "the playlist's next state", parse_no_words},
    {"prev", CommandKind::Prev, "prev", "the playlist's previous state", parse_no_words},
    {"print-state", CommandKind::PrintState, "print-state", "`state K/N: TITLE`", parse_no_words},
};

}  // namespace

std::span<const ScriptVerb> playlist_verbs() { return kVerbs; }

}  // namespace viz
