// Whether a terminal is gone: an ssh connection that dropped hangs its pty up, and reads
// then return nothing forever (the same as "no key yet" in raw mode), so the game loop
// asks poll(2) instead.
#pragma once

namespace fts::client {

// True when fd reports a hang-up or an error (POLLHUP, POLLERR, POLLNVAL); never blocks.
bool hung_up(int fd);

}  // namespace fts::client
