// fts-client's per-server token file: what a restarted client reads back.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "net/session_store.hpp"

using namespace fts::client;

namespace {
std::string temp_dir() {
  char tmpl[] = "/tmp/fts-store-XXXXXX";
  const char* d = ::mkdtemp(tmpl);
  REQUIRE(d != nullptr);
  return d;
}
}  // namespace

TEST_CASE("Session store: the state directory follows XDG", "[client][session]") {
  CHECK(state_dir("/x/state", "/home/ann") == "/x/state");
  CHECK(state_dir("relative", "/home/ann") == "/home/ann/.local/state");  // XDG: absolute only
  CHECK(state_dir(nullptr, "/home/ann") == "/home/ann/.local/state");
  CHECK(state_dir(nullptr, nullptr).empty());
}

TEST_CASE("Session store: a saved token comes back, per server, private to the user", "[client][session]") {
  const std::string dir = temp_dir();
  const std::string token = "0123456789abcdef0123456789abcdef";
  SessionStore a(dir, "127.0.0.1:7777");
  SessionStore b(dir, "example.org:7777");
  CHECK_FALSE(a.load());
  std::string why;
  REQUIRE(a.save(token, why));
  REQUIRE(a.load());
  CHECK(*a.load() == token);
  CHECK_FALSE(b.load());  // another server: nothing
  struct stat st{};
  REQUIRE(::stat(a.path().c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  a.forget();
  CHECK_FALSE(a.load());
}

TEST_CASE("Session store: a damaged file is no token", "[client][session]") {
  const std::string dir = temp_dir();
  SessionStore s(dir, "h:1");
  std::string why;
  REQUIRE(s.save("0123456789abcdef0123456789abcdef", why));
  std::ofstream(s.path()) << "not a token\n";
  CHECK_FALSE(s.load());
}

TEST_CASE("Session store: no directory, nothing kept, a clear reason", "[client][session]") {
  SessionStore s("", "h:1");
  std::string why;
  CHECK_FALSE(s.save("0123456789abcdef0123456789abcdef", why));
  CHECK(why.find("HOME") != std::string::npos);
  CHECK_FALSE(s.load());
}
