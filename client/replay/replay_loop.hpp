// fts-client --replay FILE: the terminal loop around a Replay (keys, frames, time).
#pragma once

#include <string>

namespace fts::client {

// Plays the record at `path` in this terminal until q (the field in braille dots when
// `fine`). Returns the exit code; `message` says why on failure (an unreadable or damaged
// record).
int run_replay(const std::string& path, bool kitty, bool fine, std::string& message);

}  // namespace fts::client
