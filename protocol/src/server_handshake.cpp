// The server's side of the handshake (PROTOCOL.md 5): what a hello proves (Handshake,
// handshake.hpp: the cookie, the name, the keys, the identity, the token), then the
// endpoint's part: a player taken back or a new one admitted, and the sealed welcome.
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
  if (auto it = rooms_.find(s.room); it != rooms_.end()) w.server_tick = it->second.tick;
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

Handshake::Handshake(const ServerKey& key, std::uint64_t cookie_lifetime_ms)
    : key_(key),
      cookie_lifetime_ms_(cookie_lifetime_ms),
      kx_(kx_keypair_from_seed(derive_kx_seed(key))),
      kx_hex_(public_key_hex(kx_.public_key)) {}

Challenge Handshake::challenge(const Address& from, std::uint64_t now_ms) const {
  return Challenge{make_cookie(key_, from, now_ms), kx_hex_};
}

std::optional<HelloAnswer> Handshake::screen(const Address& from, const Hello& hello, std::uint64_t now_ms) const {
  if (hello.cookie.empty()) return HelloAnswer{std::nullopt, challenge(from, now_ms)};
  switch (check_cookie(key_, from, hello.cookie, now_ms, cookie_lifetime_ms_)) {
    case CookieCheck::forged: return HelloAnswer{Reject::bad_cookie, std::nullopt};
    case CookieCheck::expired: return HelloAnswer{Reject::bad_cookie, challenge(from, now_ms)};
    case CookieCheck::ok: break;
  }
  if (const std::string why = name_problem(hello.name); !why.empty())
    return HelloAnswer{Reject::out_of_range, make_error(ErrorCode::bad_name, why)};
  return std::nullopt;
}

std::variant<ProvenHello, HelloAnswer> Handshake::prove(const Address& from, const Hello& hello, AddressLimits& limits,
                                                        std::uint64_t now_ms) const {
  // The session's keys (PROTOCOL.md 5.7), and the token, which travels sealed with them.
  const auto client_key = parse_public_key(hello.key);
  const auto keys = client_key ? server_session_keys(kx_, *client_key) : std::nullopt;
  if (!keys) return HelloAnswer{Reject::bad_key, make_error(ErrorCode::bad_key, "the hello has no usable key (PROTOCOL.md 5.7)")};
  ProvenHello proven{*keys, "", ""};
  // The player's identity, proven over this handshake (PROTOCOL.md 5.8); "" a guest.
  if (!hello.id.empty()) {
    auto fp = open_hello_identity(*keys, *client_key, kx_.public_key, hello.cookie, hello.id);
    if (!fp)
      return HelloAnswer{Reject::bad_identity,
                         make_error(ErrorCode::bad_identity, "the hello's identity proof does not verify (PROTOCOL.md 5.8)")};
    proven.identity = std::move(*fp);
  }
  if (!hello.token.empty()) {
    // Reconnects are rate limited per host: a token cannot be tried, or a player taken
    // back and forth, faster than this.
    if (AddressLimits::Host* host = limits.of(host_of(from), now_ms); host && !host->takeovers.take(now_ms))
      return HelloAnswer{Reject::takeover_limited,
                         make_error(ErrorCode::rate_limited, "too many reconnects from this address; try again soon")};
    proven.token = open_hello_token(*keys, *client_key, hello.token).value_or("-");
  }
  return proven;
}

// A hello: the handshake's proofs (Handshake), then a player taken back (by its token, or
// by its identity while it is away) or a new one admitted (the host picks its room).
void ServerEndpoint::handle_hello(const Address& from, const Header& header, const Hello& hello,
                                  std::size_t request_bytes, std::uint64_t now_ms) {
  const Encoding enc = header.encoding;
  const auto answer = [&](const HelloAnswer& a) {
    if (a.counted) rejects_.add(*a.counted);
    if (a.reply) reply_unconnected(from, enc, 0, *a.reply, request_bytes);
  };
  if (const auto a = handshake_.screen(from, hello, now_ms)) return answer(*a);
  Session* here = sessions_.at_address(from);
  // The same connection attempt again (a lost welcome, a duplicated or resent hello):
  // the same welcome, whatever was heard on the session since. Idempotent.
  if (here && here->connected && here->nonce == hello.nonce)
    return send_welcome(*here, here->welcomed_as_reconnect, request_bytes, now_ms);
  auto proof = handshake_.prove(from, hello, limits_, now_ms);
  if (const auto* a = std::get_if<HelloAnswer>(&proof)) return answer(*a);
  const ProvenHello& proven = std::get<ProvenHello>(proof);
  // A new attempt from the address of a live session: the client there restarted.
  // With that session's token it is taken back below; otherwise the old client is gone.
  // Without a token, a proven identity takes back its player who is away (not connected:
  // its seat held, or kept while its room's match runs, or restored by --resume): the
  // same player, as with the token (issue 41). A spectate hello watches as someone new.
  Session* back = nullptr;
  if (proven.token.empty() && !proven.identity.empty() && hello.join != "spectate") {
    for (auto& [pid, s] : sessions_)
      if (s.identity == proven.identity && !s.spectator && (!s.connected || &s == here)) {
        back = &s;
        break;
      }
  }
  if (here && here->connected && proven.token != here->token && here != back) {
    drop_connection(*here, "replaced by a new connection", now_ms);
    // A session that never played holds no slot (PROTOCOL.md 6): freed now, its token dead.
    if (!here->played) release(here->player_id, "replaced");
  }
  const bool returning = !proven.token.empty() || back;
  auto taken = returning ? take_back(back, from, enc, hello, proven, now_ms) : admit_new(from, enc, hello, proven, now_ms);
  if (const auto* a = std::get_if<HelloAnswer>(&taken)) return answer(*a);
  send_welcome(*std::get<Session*>(taken), returning, request_bytes, now_ms);
}

// A player taken back: `back` (found by its identity) or else the session whose token
// the hello brought. A refusal changes nothing.
std::variant<ServerEndpoint::Session*, HelloAnswer> ServerEndpoint::take_back(Session* back, const Address& from,
                                                                              Encoding enc, const Hello& hello,
                                                                              const ProvenHello& proven,
                                                                              std::uint64_t now_ms) {
  const std::string& token = proven.token;
  const bool by_token = !back;
  if (!back) {
    // A restored session knows only its token's verifier (compared once per hello).
    const std::string verifier = token_verifier(token);
    auto it = std::find_if(sessions_.begin(), sessions_.end(), [&](const auto& kv) {
      return kv.second.token.empty() ? kv.second.verifier == verifier : kv.second.token == token;
    });
    // A token is its player's; with another player's identity it takes nothing back.
    if (it != sessions_.end() && !proven.identity.empty() && !it->second.identity.empty() &&
        it->second.identity != proven.identity)
      it = sessions_.end();
    if (it == sessions_.end())
      return HelloAnswer{Reject::bad_token,
                         make_error(ErrorCode::bad_token, "unknown or expired session token; connect again without one")};
    back = &it->second;
  }
  Session& s = *back;
  // A player who quit gave its seat up: it comes back only to a free one.
  if (s.quit && !s.spectator && seats_in_room(s.room) >= config_.max_players)
    return HelloAnswer{Reject::join_refused,
                       make_error(ErrorCode::room_full, "room " + s.room_code + " has no free seat; try again later")};
  if (by_token) s.token = token;  // (a restored session knew only its verifier)
  if (s.identity.empty()) s.identity = proven.identity;  // a guest's player proven now
  if (s.token.empty()) {
    // Taken back by its identity after a restart (--resume): the journal kept only the
    // old token's verifier, so the player gets a new token (and the host a new verifier).
    s.token = derive_token(config_.key, sessions_made_ + 1);
    s.verifier = token_verifier(s.token);
  }
  // The token from another address takes the session over; the old address is told.
  if (s.connected && s.address != from)
    send_packet(s, {make_error(ErrorCode::taken_over, "another connection took this player over with its token")}, false, now_ms);
  start_session(s, from, enc, hello, proven.keys, now_ms);
  s.welcomed_as_reconnect = true;
  const char* how = token.empty() ? ServerEvent::kByIdentity : ServerEvent::kByToken;
  events_.push_back({ServerEvent::Kind::reconnected, s.player_id, s.name, how, false, s.room, s.spectator, s.identity});
  return &s;
}

// A new player: the server's and its host's caps, a player id, then the host's room
// (ServerConfig::admit) last, so that a refused hello makes no room.
std::variant<ServerEndpoint::Session*, HelloAnswer> ServerEndpoint::admit_new(const Address& from, Encoding enc,
                                                                              const Hello& hello,
                                                                              const ProvenHello& proven,
                                                                              std::uint64_t now_ms) {
  const HelloAnswer full{Reject::server_full,
                         make_error(ErrorCode::server_full, "the server has no room for more players; try again later")};
  if (sessions_.size() >= config_.max_sessions()) return full;
  // A spectate hello asks for no seat: it is held to the host's spectator cap instead.
  const bool watching = hello.join == "spectate";
  const std::size_t cap = watching ? config_.max_spectators_per_address : config_.max_sessions_per_address;
  if (sessions_from(host_of(from), watching) >= cap)
    return HelloAnswer{Reject::address_full,
                       make_error(ErrorCode::address_full, "this address has " + std::to_string(cap) +
                                                               (watching ? " spectators" : " players") +
                                                               " already; no more from it")};
  // Ids are never reused nor given where a room from another server took them; when
  // they run out the server takes nobody new (SessionTable::next_player_id).
  const std::uint32_t player_id = sessions_.next_player_id();
  if (player_id == kNoPlayerIdLeft) return full;
  // A host that named too many rooms that do not exist is guessing codes (10.1).
  const bool by_code = hello.join == "join" || watching;
  AddressLimits::Host* host = by_code ? limits_.of(host_of(from), now_ms) : nullptr;
  if (host && !host->code_misses.has(now_ms))
    return HelloAnswer{Reject::code_limited, make_error(ErrorCode::rate_limited,
                                                        "too many unknown room codes from this address; try again in a minute")};
  const Admission admission = config_.admit(JoinAsk{hello.join, hello.room, from});
  if (admission.error || admission.room == 0) {
    const bool unknown = admission.error == ErrorCode::no_such_room;
    if (unknown && host) (void)host->code_misses.take(now_ms);
    return HelloAnswer{unknown ? Reject::unknown_room : Reject::join_refused,
                       make_error(admission.error.value_or(ErrorCode::refused), admission.message.substr(0, kMaxTextBytes))};
  }
  rooms_[admission.room].tick = admission.server_tick;
  reserve_player_ids(player_id);
  Session& s = sessions_[player_id];
  s.player_id = player_id;
  s.name = hello.name;
  s.token = derive_token(config_.key, sessions_made_ + 1);
  s.verifier = token_verifier(s.token);
  s.room = admission.room;
  s.room_code = admission.code;
  s.spectator = admission.spectator;
  s.identity = proven.identity;
  start_session(s, from, enc, hello, proven.keys, now_ms);
  events_.push_back({ServerEvent::Kind::connected, s.player_id, s.name, "", false, s.room, s.spectator, s.identity});
  return &s;
}


}  // namespace fts::protocol
