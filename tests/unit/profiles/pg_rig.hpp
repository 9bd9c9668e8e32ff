// A real PostgreSQL 15 for a test (tests/support/pg_temp.sh): its own directory and a
// free port, stopped and removed at the end. available() is false (the test says so and
// checks nothing more) where the postgresql package is not installed.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace fts::test {

// A TCP port nobody listens on now (the kernel's pick).
inline int free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

class PgRig {
 public:
  // fsync off for tests (they measure nothing); on for a benchmark, as a host runs it.
  explicit PgRig(bool fsync = false) : fsync_(fsync) {
    char tmpl[] = "/tmp/fts-pg-XXXXXX";
    dir_ = ::mkdtemp(tmpl);
    port_ = free_tcp_port();
    status_ = run("start");
  }
  ~PgRig() {
    run("stop");
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  bool available() const { return status_ == 0; }
  int status() const { return status_; }  // 77: no PostgreSQL here
  bool start() { return run("start") == 0; }
  bool stop() { return run("stop") == 0; }
  std::string url() const {
    return "postgresql://fts@127.0.0.1:" + std::to_string(port_) + "/postgres?connect_timeout=2";
  }
  int port() const { return port_; }

 private:
  int run(const std::string& cmd) const {
    const std::string line = std::string("FTS_PG_FSYNC=") + (fsync_ ? "on" : "off") + " bash " FTS_SOURCE_DIR "/tests/support/pg_temp.sh " + cmd + " " + dir_ +
                             "/pg " + std::to_string(port_) + " >/dev/null 2>&1";
    const int rc = std::system(line.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  }
  std::string dir_;
  int port_ = 0;
  int status_ = -1;
  bool fsync_ = false;
};

}  // namespace fts::test
