// Address parsing for the programs' command lines (no resolution, no socket).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace fts::io {

struct HostPort {
  std::string host;  // a name or an address, without the brackets of "[::1]"
  std::string port;  // digits or a service name, resolved later
};

// "HOST:PORT", split at the last colon ("[::1]:7777" gives "::1" and "7777"); nothing
// when either half is empty or there is no colon.
std::optional<HostPort> parse_host_port(std::string_view text);
// The other way: "HOST:PORT", an IPv6 host in brackets ("[::1]:7777").
std::string host_port_text(std::string_view host, unsigned port);

// True for a numeric IPv4 or IPv6 address ("0.0.0.0", "::1"), the form a bind takes.
bool is_ip_address(const std::string& text);

}  // namespace fts::io
