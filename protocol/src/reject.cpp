#include "fts/protocol/reject.hpp"

namespace fts::protocol {

std::string_view to_string(Reject reason) {
  switch (reason) {
    case Reject::truncated: return "truncated";
    case Reject::oversize: return "oversize";
    case Reject::wrong_protocol_id: return "wrong_protocol_id";
    case Reject::bad_version: return "bad_version";
    case Reject::bad_flags: return "bad_flags";
    case Reject::garbage: return "garbage";
    case Reject::unknown_type: return "unknown_type";
    case Reject::out_of_range: return "out_of_range";
    case Reject::unpadded_hello: return "unpadded_hello";
    case Reject::bad_cookie: return "bad_cookie";
    case Reject::bad_token: return "bad_token";
    case Reject::unknown_session: return "unknown_session";
    case Reject::address_mismatch: return "address_mismatch";
    case Reject::unexpected: return "unexpected";
    case Reject::server_full: return "server_full";
    case Reject::unknown_base: return "unknown_base";
    case Reject::stale: return "stale";
    case Reject::rate_limited: return "rate_limited";
    case Reject::overflow: return "overflow";
    case Reject::address_full: return "address_full";
    case Reject::idle: return "idle";
    case Reject::join_refused: return "join_refused";
    case Reject::forged: return "forged";
    case Reject::replayed: return "replayed";
    case Reject::bad_key: return "bad_key";
    case Reject::takeover_limited: return "takeover_limited";
    case Reject::bad_field: return "bad_field";
    case Reject::unknown_room: return "unknown_room";
    case Reject::code_limited: return "code_limited";
    case Reject::count_: break;
  }
  return "unknown";
}

}  // namespace fts::protocol
