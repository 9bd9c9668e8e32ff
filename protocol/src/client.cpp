#include "fts/protocol/client.hpp"

#include <algorithm>
#include <cstdio>
#include <random>

#include "control_tables.hpp"

namespace fts::protocol {

const char* to_string(ClientState state) {
  switch (state) {
    case ClientState::idle: return "idle";
    case ClientState::connecting: return "connecting";
    case ClientState::connected: return "connected";
    case ClientState::refused: return "refused";
    case ClientState::timed_out: return "timed_out";
    case ClientState::disconnected: return "disconnected";
  }
  return "?";
}

ClientEndpoint::ClientEndpoint(ClientConfig config) : config_(std::move(config)) {}

void ClientEndpoint::connect(std::uint64_t now_ms) {
  const ClientConfig config = config_;
  *this = ClientEndpoint(config);
  kx_ = kx_random_keypair();
  state_ = ClientState::connecting;
  connect_start_ms_ = now_ms;
  std::uint64_t nonce = config_.nonce;
  if (nonce == 0) {
    std::random_device rd;
    nonce = (std::uint64_t{rd()} << 32) ^ rd();
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(nonce));
  nonce_ = hex;
  send_hello(now_ms);
}

// Before the welcome (session 0) in clear, after it sealed (PROTOCOL.md 5.7).
void ClientEndpoint::emit(const Header& header, const std::vector<Message>& messages) {
  auto bytes = header.session != 0 ? encode_sealed(seal_, header, messages) : encode_datagram(header, messages);
  if (bytes.size() > kMaxDatagramBytes) return;  // never happens with our limits; never send it
  ++stats_.datagrams_sent;
  stats_.bytes_sent += bytes.size();
  out_.push_back(std::move(bytes));
}

void ClientEndpoint::send_hello(std::uint64_t now_ms) {
  Header h;
  h.version = config_.version;
  h.encoding = config_.encoding;
  // The token goes only in a hello with a cookie, sealed with this attempt's keys.
  const std::string token = seal_.ready() && !config_.token.empty()
                                ? seal_hello_token(keys_, kx_.public_key, config_.token)
                                : std::string();
  Hello hello{config_.name, token, cookie_, "", nonce_, config_.join, config_.room, public_key_hex(kx_.public_key)};
  // The identity too, proven over this handshake (PROTOCOL.md 5.8).
  if (seal_.ready() && config_.identity)
    hello.id = seal_hello_identity(*config_.identity, keys_, kx_.public_key, server_kx_, cookie_);
  // Pad to kMinHelloBytes (a longer pad may need a longer length prefix: loop).
  for (;;) {
    const std::size_t size = kHeaderBytes + encode_payload(config_.encoding, {hello}).size();
    if (size >= kMinHelloBytes) break;
    hello.pad.append(kMinHelloBytes - size, '.');
  }
  emit(h, {hello});
  last_hello_ms_ = now_ms;
}

void ClientEndpoint::send_packet(std::uint64_t now_ms) {
  Header h;
  h.version = config_.version;
  h.encoding = config_.encoding;
  h.session = session_;
  acks_.stamp(h, now_ms);
  std::vector<Message> messages;
  messages.push_back(Input{snapshots_.latest_tick(), {inputs_.rbegin(), inputs_.rend()}});
  for (auto& c : commands_.collect(h.sequence, now_ms, config_.resend_ms, 8)) messages.push_back(c);
  emit(h, messages);
  last_send_ms_ = now_ms;
}

std::uint32_t ClientEndpoint::send_input(InputFrame frame, std::uint64_t now_ms) {
  if (state_ != ClientState::connected) return 0;
  frame.seq = next_input_seq_++;
  inputs_.push_back(frame);
  while (inputs_.size() > std::clamp<std::size_t>(config_.input_redundancy, 1, kMaxInputFrames))
    inputs_.pop_front();
  send_packet(now_ms);
  return frame.seq;
}

std::uint32_t ClientEndpoint::hold_input(InputFrame frame, std::uint64_t now_ms) {
  if (state_ != ClientState::connected) return 0;
  fire_pending_ = fire_pending_ || frame.fire;
  frame.fire = fire_pending_;
  const bool changed = !last_held_ || frame.move_x != last_held_->move_x || frame.move_y != last_held_->move_y ||
                       frame.fire;
  const std::uint64_t since = now_ms - last_held_ms_;
  if (last_held_ && since < (changed ? config_.input_min_interval_ms : config_.input_keepalive_ms)) return 0;
  fire_pending_ = false;
  last_held_ = frame;
  last_held_ms_ = now_ms;
  return send_input(frame, now_ms);
}

std::uint32_t ClientEndpoint::send_command(CommandOp op, char item, std::uint64_t now_ms) {
  if (state_ != ClientState::connected) return 0;
  const std::uint32_t rid = commands_.push(Command{0, op, op == CommandOp::buy ? item : char{0}, {}, {}});
  send_packet(now_ms);
  return rid;
}

std::uint32_t ClientEndpoint::send_chat(const std::string& text, std::uint64_t now_ms) {
  if (state_ != ClientState::connected) return 0;
  Command c{0, CommandOp::chat, 0, {}, {}};
  // Text on the wire is printable ASCII (a datagram with anything else is refused whole,
  // and a refused reliable command would block the ones after it): the rest becomes '?'.
  for (char ch : text.substr(0, kMaxTextBytes)) c.text += (ch >= 0x20 && ch < 0x7f) ? ch : '?';
  const std::uint32_t rid = commands_.push(std::move(c));
  send_packet(now_ms);
  return rid;
}

void ClientEndpoint::disconnect(std::uint64_t now_ms, const std::string& reason) {
  if (state_ == ClientState::connected) {
    for (int i = 0; i < 3; ++i) {
      Header h;
      h.version = config_.version;
      h.encoding = config_.encoding;
      h.session = session_;
      acks_.stamp(h, now_ms);
      Bye bye{reason};
      std::get<0>(wire::kByeFields).kind.clamp(bye.reason);  // what the server reads (4.9)
      emit(h, {bye});
    }
  }
  state_ = ClientState::disconnected;
}

void ClientEndpoint::update(std::uint64_t now_ms) {
  if (state_ == ClientState::connecting) {
    if (now_ms - connect_start_ms_ >= config_.connect_timeout_ms) {
      state_ = ClientState::timed_out;
      error_ = make_error(ErrorCode::timeout, "no answer from the server during the handshake");
    } else if (now_ms - last_hello_ms_ >= config_.hello_resend_ms) {
      send_hello(now_ms);
    }
  } else if (state_ == ClientState::connected) {
    if (now_ms - last_receive_ms_ >= timeout_ms_) {
      state_ = ClientState::timed_out;
      error_ = make_error(ErrorCode::timeout, "the server stopped answering");
    } else if (now_ms - last_send_ms_ >= config_.heartbeat_ms ||
               commands_.due(now_ms, config_.resend_ms)) {
      send_packet(now_ms);
    }
  }
}

void ClientEndpoint::receive(std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  ++stats_.datagrams_received;
  stats_.bytes_received += bytes.size();
  // A datagram of a session is sealed: it is opened (replay window, tag) before any parse.
  const auto header = read_header_any_version(bytes);
  const bool sealed = header && header->session != 0 && header->version == config_.version;
  // Another session's datagram is not opened (a welcome resent for a hello that crossed
  // ours is opened by the attempt that asked for it, in connecting).
  if (sealed && state_ == ClientState::connected && header->session != session_) return reject(Reject::unknown_session);
  auto d = sealed ? open_sealed(seal_, bytes, config_.version, plain_) : decode_datagram(bytes, config_.version);
  if (!d) {
    reject(d.error());
    if (d.error() == Reject::bad_version && state_ == ClientState::connecting) {
      if (auto e = decode_version_error(bytes)) {
        error_ = *e;
        state_ = ClientState::refused;
      }
    }
    return;
  }
  if (state_ == ClientState::connecting) return handle_connecting(*d, now_ms);
  if (state_ == ClientState::connected) handle_connected(*d, now_ms);
  else reject(Reject::unexpected);
}

void ClientEndpoint::handle_connecting(const Datagram& d, std::uint64_t now_ms) {
  for (const auto& m : d.messages) {
    if (const auto* c = std::get_if<Challenge>(&m); c && d.header.session == 0) {
      // The server's key gives this attempt's session keys (the same server key each time).
      const auto server_key = parse_public_key(c->key);
      const auto keys = server_key ? client_session_keys(kx_, *server_key) : std::nullopt;
      if (!keys) {
        reject(Reject::bad_key);
        continue;
      }
      keys_ = *keys;
      server_kx_ = *server_key;
      seal_ = SealedChannel(keys_, SealDirection::client_to_server, SealDirection::server_to_client);
      cookie_ = c->cookie;
      send_hello(now_ms);
    } else if (const auto* w = std::get_if<Welcome>(&m); w && d.header.session != 0) {
      welcome_ = *w;
      session_ = d.header.session;
      timeout_ms_ = std::max<std::uint64_t>(w->timeout_ms, 1);
      config_.input_redundancy = std::max<std::size_t>(config_.input_redundancy, w->input_redundancy);
      config_.token = w->token;
      state_ = ClientState::connected;
      last_receive_ms_ = now_ms;
      send_packet(now_ms);  // first ack: the server knows the welcome arrived
    } else if (const auto* e = std::get_if<Error>(&m)) {
      error_ = *e;
      state_ = ClientState::refused;
    } else {
      reject(Reject::unexpected);
    }
  }
}

void ClientEndpoint::handle_connected(const Datagram& d, std::uint64_t now_ms) {
  if (d.header.session != session_) {
    // A welcome resent for a hello that crossed ours is harmless; anything else is not ours.
    reject(d.header.session == 0 ? Reject::unexpected : Reject::unknown_session);
    return;
  }
  if (d.messages.size() == 1 && std::holds_alternative<Welcome>(d.messages[0])) return;  // resent
  std::vector<std::uint16_t> acked;
  if (!acks_.on_receive(d.header, now_ms, acked)) {
    reject(Reject::stale);
    return;
  }
  last_receive_ms_ = now_ms;
  for (auto seq : acked) commands_.on_acked(seq);
  for (const auto& m : d.messages) {
    if (const auto* s = std::get_if<SnapshotMsg>(&m)) {
      auto r = snapshots_.accept(*s);
      if (!r) reject(r.error());
      else if (*r) {
        ++stats_.snapshots_received;
        new_snapshots_.push_back(std::move(**r));
      }
    } else if (const auto* res = std::get_if<Result>(&m)) {
      if (auto why = results_.accept(*res)) reject(*why);
    } else if (const auto* chat = std::get_if<Chat>(&m)) {
      if (auto why = chats_.accept(*chat)) reject(*why);
    } else if (const auto* board = std::get_if<Leaderboard>(&m)) {
      if (boards_.size() >= kMaxBoards) boards_.erase(boards_.begin());
      boards_.push_back(*board);
    } else if (std::holds_alternative<Ping>(m)) {
    } else if (const auto* bye = std::get_if<Bye>(&m)) {
      error_ = make_error(ErrorCode::bye, bye->reason);
      state_ = ClientState::disconnected;
    } else if (const auto* moved = std::get_if<Moved>(&m)) {
      moved_ = *moved;  // the connection follows it (ClientConnection)
      state_ = ClientState::disconnected;
    } else if (const auto* e = std::get_if<Error>(&m)) {
      error_ = *e;
      state_ = ClientState::refused;
    } else {
      reject(Reject::unexpected);
    }
  }
}

std::vector<std::vector<std::uint8_t>> ClientEndpoint::take_datagrams() { return std::exchange(out_, {}); }
std::vector<Result> ClientEndpoint::take_results() { return results_.take(); }
std::vector<Snapshot> ClientEndpoint::take_snapshots() { return std::exchange(new_snapshots_, {}); }

ClientStats ClientEndpoint::stats() const {
  ClientStats s = stats_;
  s.rtt_ms = acks_.rtt_ms();
  return s;
}

}  // namespace fts::protocol
