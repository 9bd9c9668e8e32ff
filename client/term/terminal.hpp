// The terminal as the game uses it: raw keys, the alternate screen, a hidden cursor and
// the kitty keyboard protocol, all undone on every way out (normal exit, atexit, SIGINT,
// SIGTERM, SIGHUP, SIGSEGV, SIGABRT). Signals that ask to stop set a flag the main loop
// reads; crashes restore the terminal and re-raise. A terminal that hangs up (an ssh
// connection gone) stops the loop too, even where no SIGHUP reaches us.
#pragma once

#include <string_view>

#include "ui/screen.hpp"

namespace fts::client::term {

// Enters game mode on stdin/stdout. Returns false (and changes nothing) when stdin or
// stdout is not a terminal. kitty_keys asks whether the terminal speaks the kitty
// protocol; the flags are pushed by push_kitty once it answers (KeyReader does).
bool enter(bool kitty_keys, bool mouse = false);
// Pushes the kitty flags (popped again by leave) and asks again, so that the answer
// tells whether releases will be reported.
void push_kitty();
// The terminal hung up: stop_signal() says SIGHUP from now on.
void note_hangup();
// Restores the terminal; safe to call more than once and from a signal handler.
void leave();
// The terminal's size now (80x24 when unknown).
TerminalSize size();
// True once after a SIGWINCH.
bool take_resized();
// The signal that asked us to stop (SIGINT, SIGTERM, SIGHUP), or 0.
int stop_signal();
// Writes all of it to stdout (retries short writes).
void write_all(std::string_view bytes);

}  // namespace fts::client::term
