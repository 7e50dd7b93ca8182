// The lecture playlist: states and their commands with the file's line numbers, the errors
// with FILE:LINE, and which states are applied when moving forward and back.
#include <gtest/gtest.h>

#include "playlist.h"

namespace viz {
namespace {

TEST(Playlist, StatesHoldTheirCommandsWithFileLines) {
  const std::string text =
      "# lecture\n"
      "\n"
      "state The grid   # a comment\n"
      "scene procedural:cornell\n"
      "structure grid\n"
      "state Its walk\n"
      "\n"
      "step 12\n"
      "state Empty state\n";
  auto p = parse_playlist(text, "talk.txt");
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_EQ(p.value().states.size(), 3u);
  const PlaylistState& a = p.value().states[0];
  EXPECT_EQ(a.title, "The grid");
  EXPECT_EQ(a.line, 3);
  ASSERT_EQ(a.commands.size(), 2u);
  EXPECT_EQ(a.commands[0].verb, "scene");
  EXPECT_EQ(a.commands[0].line, 4);
  EXPECT_EQ(a.commands[1].line, 5);
  ASSERT_EQ(p.value().states[1].commands.size(), 1u);
  EXPECT_EQ(p.value().states[1].commands[0].verb, "step");
  EXPECT_EQ(p.value().states[1].commands[0].line, 8);
  EXPECT_TRUE(p.value().states[2].commands.empty());
  EXPECT_EQ(state_line(p.value(), 1), "state 2/3: Its walk");
}

TEST(Playlist, ErrorsNameFileAndLine) {
  auto expect = [](const std::string& text, const std::string& message) {
    auto p = parse_playlist(text, "talk.txt");
    ASSERT_FALSE(p.ok()) << text;
    EXPECT_EQ(p.error().message, message);
  };
  expect("scene procedural:cornell\nstate A\n", "talk.txt:1: 'scene' before the first 'state TITLE' line");
  expect("state A\nstate\n", "talk.txt:2: usage: state TITLE");
  expect("state A\nscene procedural:cornell\nfly away\n", "talk.txt:3: unknown command 'fly'");
  expect("state A\nnext\n", "talk.txt:2: 'next' drives playlists; it cannot be part of a state");
  expect("# nothing\n", "talk.txt: no 'state TITLE' line: the playlist is empty");
  EXPECT_FALSE(load_playlist("/no/such/playlist.txt").ok());
}

TEST(Playlist, ForwardAppliesTheNewStatesBackReplaysFromTheFirst) {
  PlaylistCursor c;
  c.reset(4);
  bool scratch = true;
  EXPECT_EQ(c.go_to(0, &scratch), (std::vector<size_t>{0}));
  EXPECT_FALSE(scratch);
  EXPECT_EQ(c.go_to(1, &scratch), (std::vector<size_t>{1}));
  EXPECT_EQ(c.go_to(3, &scratch), (std::vector<size_t>{2, 3}));
  EXPECT_FALSE(scratch);
  EXPECT_TRUE(c.go_to(9, &scratch).empty()) << "past the end: stays on the last";
  EXPECT_EQ(c.current(), 3u);
  EXPECT_EQ(c.go_to(1, &scratch), (std::vector<size_t>{0, 1}));
  EXPECT_TRUE(scratch);
  EXPECT_EQ(c.current(), 1u);
}

}  // namespace
}  // namespace viz
