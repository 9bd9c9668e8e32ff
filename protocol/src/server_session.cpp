// One client's session on the server (server_session.hpp): its datagrams' headers and seals.
#include "fts/protocol/server_session.hpp"

#include "fts/protocol/constants.hpp"

namespace fts::protocol {

Header ServerSession::next_header(std::uint16_t version, std::uint64_t now_ms) {
  Header h;
  h.version = version;
  h.encoding = encoding;
  h.session = session_id;
  acks.stamp(h, now_ms);
  return h;
}

void ServerSession::seal_into(const Header& h, const std::vector<std::uint8_t>& payload, std::vector<Outgoing>& out,
                              std::vector<Outgoing>& spare) {
  if (spare.empty()) {
    out.emplace_back();
  } else {
    out.push_back(std::move(spare.back()));
    spare.pop_back();
  }
  Outgoing& o = out.back();
  o.to.assign(address);  // within the capacity a sent datagram's address left
  o.bytes.clear();
  seal.seal(h, payload, o.bytes);
  if (o.bytes.size() > kMaxDatagramBytes) {  // never sent; the limits make it unreachable
    spare.push_back(std::move(o));
    out.pop_back();
  }
}

}  // namespace fts::protocol
