// The server's side of the handshake (PROTOCOL.md 5): challenges, hellos with a cookie,
// the key exchange and the sealed welcome (5.7), reconnects with a token, refusals.
#include "fts/protocol/server.hpp"

#include <algorithm>

namespace fts::protocol {

// Before the handshake completes, a reply is never larger than its request.
void ServerEndpoint::reply_unconnected(const Address& to, Encoding encoding, std::uint32_t session,
                                       const Message& message, std::size_t request_bytes) {
  Header h;
  h.version = config_.version;
  h.encoding = encoding;
  h.session = session;
  auto bytes = encode_datagram(h, {message});
  if (bytes.size() > request_bytes) return;
  emit(to, std::move(bytes));
}

// The welcome is the session's first sealed datagram (it carries the token); like every
// reply before the handshake completes, it is never larger than the hello.
void ServerEndpoint::send_welcome(Session& s, bool reconnected, std::size_t request_bytes,
                                  std::uint64_t now_ms) {
  Welcome w = config_.settings;
  w.player_id = s.player_id;
  w.token = s.token;
  if (auto it = room_ticks_.find(s.room); it != room_ticks_.end()) w.server_tick = it->second;
  w.room = s.room_code;
  w.spectator = s.spectator;
  w.reconnected = reconnected;
  w.max_players = config_.max_players;
  w.timeout_ms = static_cast<std::uint32_t>(config_.timeout_ms);
  w.reconnect_window_ms = static_cast<std::uint32_t>(config_.reconnect_window_ms);
  const Header h = session_header(s, now_ms);
  auto bytes = encode_sealed(s.seal, h, {w});
  if (bytes.size() <= request_bytes) emit(s.address, std::move(bytes));  // rare: not from the pool
}

void ServerEndpoint::start_session(Session& s, const Address& from, Encoding encoding, const Hello& hello,
                                   const SessionKeys& keys, std::uint64_t now_ms) {
  sessions_.unindex(s);
  ++sessions_made_;
  s.session_id = derive_session_id(config_.key, sessions_made_);
  while (sessions_.session_id_taken(s.session_id))
    s.session_id = derive_session_id(config_.key, ++sessions_made_);
  s.address = from;
  s.encoding = encoding;
  s.connected = true;
  s.quit = false;
  s.kept = false;  // back: its reconnect window starts again at its next departure
  s.nonce = hello.nonce;
  s.seal = SealedChannel(keys, SealDirection::server_to_client, SealDirection::client_to_server);
  s.welcomed_as_reconnect = false;
  s.last_receive_ms = now_ms;
  s.last_send_ms = now_ms;
  s.last_input_seq = 0;
  s.unanswered = 0;
  s.last_active_ms = now_ms;
  s.datagrams = TokenBucket(config_.session_datagrams_per_s, config_.session_datagram_burst, now_ms);
  s.acks = AckWindow{};
  s.results = ReliableSender<Result>{};
  s.chats = ReliableSender<Chat>{};
  s.commands = ReliableReceiver<Command>{};
  s.snapshots = SnapshotSender(config_.snapshot_max_base_age_ticks, config_.settings.tick_rate_hz());
  sessions_.index(s);
}

void ServerEndpoint::handle_hello(const Address& from, const Header& header, const Hello& hello,
                                  std::size_t request_bytes, std::uint64_t now_ms) {
  const Encoding enc = header.encoding;
  if (hello.cookie.empty()) {
    reply_unconnected(from, enc, 0, Challenge{make_cookie(config_.key, from, now_ms), kx_hex_}, request_bytes);
    return;
  }
  switch (check_cookie(config_.key, from, hello.cookie, now_ms, config_.cookie_lifetime_ms)) {
    case CookieCheck::forged: return rejects_.add(Reject::bad_cookie);
    case CookieCheck::expired:
      rejects_.add(Reject::bad_cookie);
      reply_unconnected(from, enc, 0, Challenge{make_cookie(config_.key, from, now_ms), kx_hex_}, request_bytes);
      return;
    case CookieCheck::ok: break;
  }
  if (const std::string why = name_problem(hello.name); !why.empty()) {
    rejects_.add(Reject::out_of_range);
    reply_unconnected(from, enc, 0, make_error(ErrorCode::bad_name, why), request_bytes);
    return;
  }
  Session* here = nullptr;
  if ((here = sessions_.at_address(from))) {
    // The same connection attempt again (a lost welcome, a duplicated or resent hello):
    // the same welcome, whatever was heard on the session since. Idempotent.
    if (here->connected && here->nonce == hello.nonce) {
      send_welcome(*here, here->welcomed_as_reconnect, request_bytes, now_ms);
      return;
    }
  }
  // The session's keys (PROTOCOL.md 5.7), and the token, which travels sealed with them.
  const auto client_key = parse_public_key(hello.key);
  const auto keys = client_key ? server_session_keys(kx_, *client_key) : std::nullopt;
  if (!keys) {
    rejects_.add(Reject::bad_key);
    reply_unconnected(from, enc, 0, make_error(ErrorCode::bad_key, "the hello has no usable key (PROTOCOL.md 5.7)"), request_bytes);
    return;
  }
  // The player's identity, proven over this handshake (PROTOCOL.md 5.8); "" a guest.
  std::string identity;
  if (!hello.id.empty()) {
    auto fp = open_hello_identity(*keys, *client_key, kx_.public_key, hello.cookie, hello.id);
    if (!fp) {
      rejects_.add(Reject::bad_identity);
      reply_unconnected(from, enc, 0,
                        make_error(ErrorCode::bad_identity, "the hello's identity proof does not verify (PROTOCOL.md 5.8)"),
                        request_bytes);
      return;
    }
    identity = std::move(*fp);
  }
  std::string token;
  if (!hello.token.empty()) {
    // Reconnects are rate limited per host: a token cannot be tried, or a player taken
    // back and forth, faster than this.
    if (AddressLimits::Host* host = limits_.of(host_of(from), now_ms); host && !host->takeovers.take(now_ms)) {
      rejects_.add(Reject::takeover_limited);
      reply_unconnected(from, enc, 0, make_error(ErrorCode::rate_limited, "too many reconnects from this address; try again soon"),
                        request_bytes);
      return;
    }
    token = open_hello_token(*keys, *client_key, hello.token).value_or("-");
  }
  // A new attempt from the address of a live session: the client there restarted.
  // With that session's token it is taken back below; otherwise the old client is gone.
  // Without a token, a proven identity takes back its player who is away (not connected:
  // its seat held, or kept while its room's match runs, or restored by --resume): the
  // same player, as with the token (issue 41). A spectate hello watches as someone new.
  Session* back = nullptr;
  if (token.empty() && !identity.empty() && hello.join != "spectate") {
    for (auto& [pid, s] : sessions_)
      if (s.identity == identity && !s.spectator && (!s.connected || &s == here)) {
        back = &s;
        break;
      }
  }
  if (here && here->connected && token != here->token && here != back) {
    drop_connection(*here, "replaced by a new connection", now_ms);
    // A session that never played holds no slot (PROTOCOL.md 6): freed now, its token dead.
    if (!here->played) release(here->player_id, "replaced");
  }
  if (!token.empty() || back) {
    if (!back) {
      // A restored session knows only its token's verifier (compared once per hello).
      const std::string verifier = token_verifier(token);
      auto it = std::find_if(sessions_.begin(), sessions_.end(), [&](const auto& kv) {
        return kv.second.token.empty() ? kv.second.verifier == verifier : kv.second.token == token;
      });
      // A token is its player's; with another player's identity it takes nothing back.
      if (it != sessions_.end() && !identity.empty() && !it->second.identity.empty() &&
          it->second.identity != identity)
        it = sessions_.end();
      if (it == sessions_.end()) {
        rejects_.add(Reject::bad_token);
        reply_unconnected(from, enc, 0,
                          make_error(ErrorCode::bad_token, "unknown or expired session token; connect again without one"),
                          request_bytes);
        return;
      }
      back = &it->second;
      back->token = token;
    }
    Session& s = *back;
    if (s.identity.empty()) s.identity = identity;  // a guest's player proven now
    if (s.token.empty()) {
      // Taken back by its identity after a restart (--resume): the journal kept only the
      // old token's verifier, so the player gets a new token (and the host a new verifier).
      s.token = derive_token(config_.key, sessions_made_ + 1);
      s.verifier = token_verifier(s.token);
    }
    // A player who quit gave its seat up: it comes back only to a free one.
    if (s.quit && !s.spectator && seats_in_room(s.room) >= config_.max_players) {
      rejects_.add(Reject::join_refused);
      reply_unconnected(from, enc, 0,
                        make_error(ErrorCode::room_full, "room " + s.room_code + " has no free seat; try again later"),
                        request_bytes);
      return;
    }
    // The token from another address takes the session over; the old address is told.
    if (s.connected && s.address != from)
      send_packet(s, {make_error(ErrorCode::taken_over, "another connection took this player over with its token")}, false, now_ms);
    start_session(s, from, enc, hello, *keys, now_ms);
    s.welcomed_as_reconnect = true;
    events_.push_back({ServerEvent::Kind::reconnected, s.player_id, s.name, token.empty() ? "identity" : "token", false,
                       s.room, s.spectator, s.identity});
    send_welcome(s, true, request_bytes, now_ms);
    return;
  }
  if (sessions_.size() >= config_.max_sessions()) return refuse_full(from, enc, request_bytes);
  // A spectate hello asks for no seat: it is held to the host's spectator cap instead.
  const bool watching = hello.join == "spectate";
  const std::size_t cap = watching ? config_.max_spectators_per_address : config_.max_sessions_per_address;
  if (sessions_from(host_of(from), watching) >= cap) {
    rejects_.add(Reject::address_full);
    const std::string text = "this address has " + std::to_string(cap) +
                             (watching ? " spectators" : " players") + " already; no more from it";
    reply_unconnected(from, enc, 0, make_error(ErrorCode::address_full, text), request_bytes);
    return;
  }
  // Ids are never reused nor given where a room from another server took them; when
  // they run out the server takes nobody new (SessionTable::next_player_id).
  const std::uint32_t player_id = sessions_.next_player_id();
  if (player_id == kNoPlayerIdLeft) return refuse_full(from, enc, request_bytes);
  // The host picks the room last: a refused hello above creates no room.
  // A host that named too many rooms that do not exist is guessing codes (10.1).
  const bool by_code = hello.join == "join" || watching;
  AddressLimits::Host* host = by_code ? limits_.of(host_of(from), now_ms) : nullptr;
  if (host && !host->code_misses.has(now_ms)) {
    rejects_.add(Reject::code_limited);
    reply_unconnected(from, enc, 0,
                      make_error(ErrorCode::rate_limited, "too many unknown room codes from this address; try again in a minute"),
                      request_bytes);
    return;
  }
  const Admission admission = config_.admit(JoinAsk{hello.join, hello.room, from});
  if (admission.error || admission.room == 0) {
    const bool unknown = admission.error == ErrorCode::no_such_room;
    if (unknown && host) (void)host->code_misses.take(now_ms);
    rejects_.add(unknown ? Reject::unknown_room : Reject::join_refused);
    reply_unconnected(from, enc, 0,
                      make_error(admission.error.value_or(ErrorCode::refused), admission.message.substr(0, kMaxTextBytes)),
                      request_bytes);
    return;
  }
  room_ticks_[admission.room] = admission.server_tick;
  reserve_player_ids(player_id);
  Session& s = sessions_[player_id];
  s.player_id = player_id;
  s.name = hello.name;
  s.token = derive_token(config_.key, sessions_made_ + 1);
  s.verifier = token_verifier(s.token);
  s.room = admission.room;
  s.room_code = admission.code;
  s.spectator = admission.spectator;
  s.identity = identity;
  start_session(s, from, enc, hello, *keys, now_ms);
  events_.push_back({ServerEvent::Kind::connected, s.player_id, s.name, "", false, s.room, s.spectator, s.identity});
  send_welcome(s, false, request_bytes, now_ms);
}

void ServerEndpoint::refuse_full(const Address& to, Encoding encoding, std::size_t request_bytes) {
  rejects_.add(Reject::server_full);
  reply_unconnected(to, encoding, 0,
                    make_error(ErrorCode::server_full, "the server has no room for more players; try again later"),
                    request_bytes);
}

}  // namespace fts::protocol
