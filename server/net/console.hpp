// The host's console: a local UNIX stream socket (mode 0600, never on the network),
// JSON lines in and out, served from the server's io_context; and the front end
// `fts-server --console SOCKET CMD [ARGS]` that sends one command and prints the answer.
#pragma once

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
  // Binds and listens ("" on success, else why not). A stale socket file is replaced;
  // any other file at the path is left alone and is an error.
  std::string start();

  static constexpr std::size_t kMaxConnections = 8;    // more are closed at once
  static constexpr std::size_t kMaxLineBytes = 65536;  // a longer request closes its connection

 private:
  struct Connection;
  void accept();

  boost::asio::io_context& io_;
  std::string path_;
  std::function<std::string(const std::string&)> handle_;
  boost::asio::local::stream_protocol::acceptor acceptor_;
  std::shared_ptr<std::size_t> open_ = std::make_shared<std::size_t>(0);
  bool bound_ = false;
};

// Front end: sends one request (console_request of app/console_commands.hpp) to the socket and prints the reply. Exit code: 0 ok,
// 1 the server refused the command, 2 usage or connection error.
int run_console_client(const std::string& path, const std::vector<std::string>& words);

}  // namespace fts::server
