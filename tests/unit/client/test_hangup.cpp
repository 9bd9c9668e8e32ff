#include <catch2/catch.hpp>

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include "term/hangup.hpp"

using namespace fts::client;

// Issue 31: an ssh connection that drops closes the pty's master; the client's terminal
// (the slave) must then read as hung up, so that the game loop ends and gives it back.
TEST_CASE("a pty whose other side closed reads as hung up", "[client][ssh]") {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  REQUIRE(master >= 0);
  REQUIRE(::grantpt(master) == 0);
  REQUIRE(::unlockpt(master) == 0);
  const int slave = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  REQUIRE(slave >= 0);
  CHECK_FALSE(hung_up(slave));
  CHECK(::write(master, "x", 1) == 1);  // a key waiting is no hang-up
  CHECK_FALSE(hung_up(slave));
  ::close(master);
  CHECK(hung_up(slave));
  ::close(slave);
  CHECK(hung_up(slave));  // a closed descriptor too (POLLNVAL)
}
