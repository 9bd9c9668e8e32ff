// The host's console: a local UNIX stream socket (mode 0600, never on the network),
// JSON lines in and out, served from the server's io_context; and the front end
// `fts-server --console SOCKET CMD [ARGS]` that sends one command and prints the answer.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fts/io/asio.hpp"

namespace fts::server {

class ConsoleServer {
 public:
  // handle: one request line -> one reply line (without the newline).
  ConsoleServer(boost::asio::io_context& io, std::string path, std::function<std::string(const std::string&)> handle);
  ~ConsoleServer();
  // Requests answered later, off the tick (the profile database's, issue 41): `deferred`
  // takes a line it answers and returns true, and calls `reply` once, from any thread;
  // false: `handle` answers it.
  using Deferred = std::function<bool(const std::string& line, std::function<void(std::string)> reply)>;
  void set_deferred(Deferred deferred) { deferred_ = std::move(deferred); }
  // Requests read whose replies are not written yet (a drained server waits for them:
  // the reply to `handover all` comes as its last room leaves).
  std::size_t unanswered() const { return *unanswered_; }
  // Binds and listens ("" on success, else why not). A stale socket file is replaced;
  // any other file at the path is left alone and is an error.
  std::string start();

  // Every bound has a consequence. Beyond kMaxConnections a new connection is told
  // {"ok":false,"error":"console busy..."} and closed; a request line longer than
  // kMaxLineBytes closes its connection; a connection that sends no complete line, or
  // does not read its reply, within kIdleMs is closed (so a stuck or hostile client
  // never holds a slot for long). The tick loop never waits for a console client.
  static constexpr std::size_t kMaxConnections = 8;
  static constexpr std::size_t kMaxLineBytes = 65536;
  static constexpr int kIdleMs = 5000;
  // A deferred request's reply (a profile query, a hand-over of every room) may take this
  // long; the client still has kIdleMs to read it.
  static constexpr int kDeferredMs = 60000;
  struct Counters {
    std::uint64_t accepted = 0, refused_busy = 0, timed_out = 0, too_long = 0;
  };
  const Counters& counters() const { return *counters_; }

 private:
  struct Connection;
  void accept();

  boost::asio::io_context& io_;
  std::string path_;
  std::function<std::string(const std::string&)> handle_;
  Deferred deferred_;
  boost::asio::local::stream_protocol::acceptor acceptor_;
  std::shared_ptr<std::size_t> open_ = std::make_shared<std::size_t>(0);
  std::shared_ptr<std::size_t> unanswered_ = std::make_shared<std::size_t>(0);
  std::shared_ptr<Counters> counters_ = std::make_shared<Counters>();
  bool busy_logged_ = false;  // "console_busy" is logged once per busy spell
  bool bound_ = false;
};

// Front end: sends one request (console_request of app/console_commands.hpp) to the socket and prints the reply. Exit code: 0 ok,
// 1 the server refused the command, 2 usage or connection error.
int run_console_client(const std::string& path, const std::vector<std::string>& words);

}  // namespace fts::server
