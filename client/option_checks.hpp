// The checks fts-client's and fts-bot's option tables share (fts/cli/option_table.hpp).
#pragma once

#include <string>

#include "fts/cli/option_table.hpp"
#include "fts/io/address.hpp"
#include "fts/protocol/constants.hpp"

namespace fts::client {

inline bool parse_host_port_text(const std::string& text, std::string& out) {
  if (!io::parse_host_port(text)) return false;
  out = text;
  return true;
}
inline bool parse_encoding(const std::string& text, protocol::Encoding& out) {
  if (text == "json") out = protocol::Encoding::json;
  else if (text == "msgpack") out = protocol::Encoding::msgpack;
  else return false;
  return true;
}
inline std::string show_text(const std::string& v) { return v; }
inline std::string show_encoding(const protocol::Encoding& e) {
  return e == protocol::Encoding::json ? "json" : "msgpack";
}

inline constexpr cli::Custom<std::string> kHostPort{parse_host_port_text, show_text, "HOST:PORT"};
inline constexpr cli::Custom<protocol::Encoding> kEncoding{parse_encoding, show_encoding, "json, msgpack"};

}  // namespace fts::client
