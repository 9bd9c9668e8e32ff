#include "fts/protocol/server.hpp"

#include <algorithm>
#include <stdexcept>

namespace fts::protocol {
namespace {

// At least a hello's size, "FTSP", this version and session 0 (whatever the flags say).
bool hello_of_version(std::span<const std::uint8_t> bytes, std::uint16_t version) {
  return bytes.size() >= kMinHelloBytes && bytes[4] == (version >> 8) && bytes[5] == (version & 0xFF) &&
         bytes[7] == 0 && bytes[8] == 0 && bytes[9] == 0 && bytes[10] == 0;
}

AddressLimits::Rates address_rates(const ServerConfig& c) {
  AddressLimits::Rates r;
  r.datagrams_per_s = c.address_datagrams_per_s, r.datagram_burst = c.address_datagram_burst;
  r.hellos_per_s = c.hellos_per_s, r.hello_burst = c.hello_burst;
  r.takeovers_per_s = c.takeovers_per_s;
  r.takeover_burst = c.takeover_burst != 0 ? c.takeover_burst : static_cast<std::uint32_t>(c.max_sessions_per_address);
  r.code_misses_per_min = c.room_code_misses_per_min, r.code_miss_burst = c.room_code_miss_burst;
  r.max_hosts = c.max_tracked_addresses;
  return r;
}

}  // namespace

ServerEndpoint::ServerEndpoint(ServerConfig config)
    : config_(std::move(config)),
      handshake_(config_.key, config_.cookie_lifetime_ms),
      sessions_(config_.first_player_id),
      limits_(address_rates(config_)) {
  if (!config_.admit) throw std::invalid_argument("ServerConfig::admit is required: the host picks a new player's room");
}

void ServerEndpoint::emit(const Address& to, std::vector<std::uint8_t> bytes) {
  if (bytes.size() > kMaxDatagramBytes) return;  // never sent; the limits make it unreachable
  lane_.out.push_back({to, std::move(bytes)});
}

Header ServerEndpoint::session_header(Session& s, std::uint64_t now_ms) { return s.next_header(config_.version, now_ms); }

// The server's own stall (a hitch, a debugger, swap) is not the clients' silence: a gap
// between two calls longer than stall_threshold_ms moves every session's clocks forward
// by the gap, so that time-outs and reconnect windows count only time during which the
// server was receiving.
void ServerEndpoint::observe_time(std::uint64_t now_ms) {
  if (last_call_ms_ != 0 && now_ms > last_call_ms_ + config_.stall_threshold_ms) {
    const std::uint64_t gap = now_ms - last_call_ms_;
    for (auto& [id, s] : sessions_) {
      s.last_receive_ms += gap;
      s.disconnected_ms += gap;
      s.last_active_ms += gap;
    }
    stalled_ms_ += gap;
  }
  last_call_ms_ = std::max(last_call_ms_, now_ms);
}

void ServerEndpoint::receive(const Address& from, std::span<const std::uint8_t> bytes,
                             std::uint64_t now_ms) {
  serial_only("receive");
  Session* s = screen(from, bytes, now_ms);
  if (!s) return;
  applied_.clear();
  s->apply(open_sealed(s->seal, bytes, config_.version, plain_), now_ms, config_, applied_, rejects_);
  settle(s->player_id, s->session_id, applied_, now_ms);
}

ServerEndpoint::Session* ServerEndpoint::screen(const Address& from, std::span<const std::uint8_t> bytes,
                                                std::uint64_t now_ms) {
  const std::uint32_t id = screen_sender(from, bytes, now_ms);
  return id == 0 ? nullptr : session_for(sessions_.with_session_id(id), from, rejects_);
}

std::uint32_t ServerEndpoint::screen_sender(const Address& from, std::span<const std::uint8_t> bytes,
                                            std::uint64_t now_ms) {
  observe_time(now_ms);
  // Cheapest checks first: the sender's rate, the header, the session (session_for), the
  // replay window and the tag (PROTOCOL.md 5.7), then the session's rate; the payload is
  // parsed only for a datagram that passed them all, and nothing of the session changes
  // before the tag verified.
  auto drop = [&](Reject r) -> std::uint32_t {
    rejects_.add(r);
    return 0;
  };
  // A hello-sized datagram of our version that does not decode is most likely a hello
  // from a client with a bug: say why, in fewer bytes than it sent (no amplification).
  auto bad_hello = [&](Encoding encoding, Reject why) {
    const std::string text = "the server could not read this hello (" + std::string(to_string(why)) +
                             "); see PROTOCOL.md section 4.1";
    reply_unconnected(from, encoding, 0, make_error(ErrorCode::bad_hello, text), bytes.size());
  };
  AddressLimits::Host* host = limits_.of(host_of(from), now_ms);
  if (host && !host->datagrams.take(now_ms)) return drop(Reject::rate_limited);
  auto header = read_header_any_version(bytes);
  if (!header) {
    // Flags we do not know on a hello of ours (FTSP, our version, session 0): answered in
    // JSON, the encoding every client reads, within the handshake's rate.
    if (header.error() == Reject::bad_flags && hello_of_version(bytes, config_.version) &&
        (!host || host->hellos.take(now_ms)))
      bad_hello(Encoding::json, Reject::bad_flags);
    return drop(header.error());
  }
  // Handshake datagrams cost a keyed hash and a reply: 10 a second per host (ioquake3).
  if (header->session == 0 && host && !host->hellos.take(now_ms)) return drop(Reject::rate_limited);
  if (header->version != config_.version) {
    rejects_.add(Reject::bad_version);
    if (bytes.size() >= kMinHelloBytes) {
      const std::string text = "protocol version " + std::to_string(header->version) +
                               " is not supported; this server speaks version " +
                               std::to_string(config_.version) + ": update your client";
      Header h;
      h.version = config_.version;
      auto reply = encode_version_refusal(h, make_error(ErrorCode::version, text));
      if (reply.size() <= bytes.size()) emit(from, std::move(reply));
    }
    return 0;
  }
  if (header->session != 0) return header->session;
  auto d = decode_datagram(bytes, config_.version);
  if (!d) {
    rejects_.add(d.error());
    if (bytes.size() >= kMinHelloBytes) bad_hello(header->encoding, d.error());
    return 0;
  }
  if (d->messages.size() != 1 || !std::holds_alternative<Hello>(d->messages[0])) return drop(Reject::unexpected);
  if (bytes.size() < kMinHelloBytes) return drop(Reject::unpadded_hello);
  handle_hello(from, d->header, std::get<Hello>(d->messages[0]), bytes.size(), now_ms);
  return 0;
}

// A spectator holds no seat (PROTOCOL.md 5.6): it counts against its own cap per host.
std::size_t ServerEndpoint::sessions_from(std::string_view host, bool spectators) const {
  return static_cast<std::size_t>(std::count_if(sessions_.begin(), sessions_.end(), [&](const auto& kv) {
    return !kv.second.quit && kv.second.spectator == spectators && host_of(kv.second.address) == host;
  }));
}

const std::vector<const ServerSession*>& ServerEndpoint::members_of(std::uint32_t room) const {
  serial_only("members_of");  // a const read that fills a cache: never beside a pool's jobs
  if (members_generation_ != sessions_.generation()) {
    members_generation_ = sessions_.generation();
    for (auto& [r, members] : members_) members.clear();
    for (const auto& [id, s] : sessions_) members_[s.room].push_back(&s);
    std::erase_if(members_, [](const auto& kv) { return kv.second.empty(); });
  }
  static const std::vector<const ServerSession*> kNone;
  const auto it = members_.find(room);
  return it == members_.end() ? kNone : it->second;
}

std::size_t ServerEndpoint::seats_in_room(std::uint32_t room) const {
  const auto& m = members_of(room);
  return static_cast<std::size_t>(std::count_if(m.begin(), m.end(), [](const Session* s) { return !s->quit && !s->spectator; }));
}

std::size_t ServerEndpoint::spectators_in_room(std::uint32_t room) const {
  const auto& m = members_of(room);
  return static_cast<std::size_t>(std::count_if(m.begin(), m.end(), [](const Session* s) { return s->spectator && s->connected; }));
}

std::size_t ServerEndpoint::holding_in_room(std::uint32_t room) const {
  const auto& m = members_of(room);
  return static_cast<std::size_t>(std::count_if(m.begin(), m.end(), [](const Session* s) { return s->connected || s->played; }));
}

std::size_t ServerEndpoint::sessions_in_room(std::uint32_t room) const { return members_of(room).size(); }

std::vector<std::uint32_t> ServerEndpoint::connected_in_room(std::uint32_t room) const {
  std::vector<std::uint32_t> out;
  for (const Session* s : members_of(room))
    if (s->connected) out.push_back(s->player_id);
  return out;
}

const std::map<std::uint32_t, RoomSessions>& ServerEndpoint::connected_by_room() {
  serial_only("connected_by_room");
  refresh_rooms();
  return by_room_;
}

void ServerEndpoint::refresh_rooms() {
  if (by_room_generation_ == sessions_.generation()) return;
  by_room_generation_ = sessions_.generation();
  for (auto& [room, members] : by_room_) members.sessions_.clear();
  held_.clear();
  for (auto& [id, s] : sessions_) {
    if (!s.connected) {
      held_.push_back(&s);
      continue;
    }
    RoomSessions& members = by_room_[s.room];
    members.version_ = config_.version;
    members.sessions_.push_back(&s);
  }
  std::erase_if(by_room_, [](const auto& kv) { return kv.second.empty(); });
}

void ServerEndpoint::send_packet(Session& s, std::vector<Message> messages, bool with_results,
                                 std::uint64_t now_ms) {
  seal_packet(s, config_.version, std::move(messages), with_results, config_.resend_ms, now_ms, lane_);
}

void seal_packet(ServerSession& s, std::uint16_t version, std::vector<Message> messages, bool with_results,
                 std::uint64_t resend_ms, std::uint64_t now_ms, SendLane& lane) {
  const Header h = s.next_header(version, now_ms);
  s.last_send_ms = now_ms;
  if (with_results) {
    for (auto& r : s.results.collect(h.sequence, now_ms, resend_ms, 3)) messages.push_back(std::move(r));
    for (auto& c : s.chats.collect(h.sequence, now_ms, resend_ms, 2)) messages.push_back(std::move(c));
  }
  if (messages.empty()) messages.push_back(Ping{});
  lane.payload.clear();
  append_payload(h.encoding, messages, lane.payload);
  s.seal_into(h, lane.payload, lane.out, lane.spare);
}

void ServerEndpoint::send_snapshot(std::uint32_t player_id, const Snapshot& snapshot, std::uint64_t now_ms) {
  serial_only("send_snapshot");
  send_snapshot(player_id, std::make_shared<const Snapshot>(quantize(snapshot)), now_ms);
}

namespace {

// `quantized` to each of `sessions` (a delta against what each acknowledged, in as many
// parts as it takes), sealed into `lane`. Sessions with the same base and encoding (most
// of a room's, when they acknowledge in time) get the same parts: made and encoded once,
// straight from the sender's buffers, then stamped and sealed for each.
void seal_snapshots(std::span<ServerSession* const> sessions, std::uint16_t version, const SharedSnapshot& quantized,
                    std::uint64_t now_ms, SendLane& lane) {
  lane.encoded_used = 0;
  for (ServerSession* s : sessions) {
    const Snapshot* base = s->snapshots.base_for(*quantized);
    const auto used = lane.encoded.begin() + static_cast<std::ptrdiff_t>(lane.encoded_used);
    auto e = std::find_if(lane.encoded.begin(), used,
                          [&](const SendLane::Encoded& x) { return x.base == base && x.encoding == s->encoding; });
    if (e == used) {  // the first session with this base: its parts are encoded for the others too
      if (lane.encoded_used == lane.encoded.size()) lane.encoded.emplace_back();
      e = lane.encoded.begin() + static_cast<std::ptrdiff_t>(lane.encoded_used++);
      e->base = base;
      e->encoding = s->encoding;
      e->parts = 0;
      for (const SnapshotMsg& part : s->snapshots.encode(quantized, s->encoding)) {
        if (e->parts == e->payloads.size()) e->payloads.emplace_back();
        std::vector<std::uint8_t>& payload = e->payloads[e->parts++];
        payload.clear();
        append_snapshot_payload(s->encoding, part, payload);
      }
    } else {
      s->snapshots.sent(quantized);
    }
    for (std::size_t k = 0; k < e->parts; ++k) {
      const Header h = s->next_header(version, now_ms);
      s->last_send_ms = now_ms;
      s->seal_into(h, e->payloads[k], lane.out, lane.spare);
    }
  }
}

}  // namespace

void RoomSessions::send_snapshot(const SharedSnapshot& quantized, std::uint64_t now_ms, SendLane& lane) const {
  seal_snapshots(sessions_, version_, quantized, now_ms, lane);
}

void ServerEndpoint::send_snapshot(std::uint32_t player_id, const SharedSnapshot& quantized, std::uint64_t now_ms) {
  serial_only("send_snapshot");
  auto it = sessions_.find(player_id);
  if (it == sessions_.end() || !it->second.connected) return;
  ServerSession* const one = &it->second;
  seal_snapshots({&one, 1}, config_.version, quantized, now_ms, lane_);
}

void ServerEndpoint::adopt(SendLane& lane) {
  serial_only("adopt");
  for (Outgoing& o : lane.out) lane_.out.push_back(std::move(o));
  const std::size_t used = lane.out.size();
  lane.out.clear();
  // The lane gets back as many sent buffers as it used, when the endpoint has them.
  while (lane.spare.size() < used && !lane_.spare.empty()) {
    lane.spare.push_back(std::move(lane_.spare.back()));
    lane_.spare.pop_back();
  }
}

void ServerEndpoint::send_result(std::uint32_t player_id, std::uint32_t command_rid, ResultCode code,
                                 std::string message, std::uint64_t now_ms) {
  serial_only("send_result");
  auto it = sessions_.find(player_id);
  if (it == sessions_.end()) return;
  // Sent by the timers' next run (update, timer_jobs), batched with the session's other due results.
  if (!it->second.answer(command_rid, code, std::move(message), config_.max_pending_results))
    overflow(it->second, "results", now_ms);
}

bool ServerEndpoint::send_board(std::uint32_t player_id, const Leaderboard& board, std::uint64_t now_ms) {
  serial_only("send_board");
  auto it = sessions_.find(player_id);
  if (it == sessions_.end() || !it->second.connected) return false;
  send_packet(it->second, {board}, false, now_ms);
  return true;
}

std::vector<Outgoing> ServerEndpoint::take_datagrams() {
  serial_only("take_datagrams");
  return std::exchange(lane_.out, {});
}
void ServerEndpoint::take_datagrams(std::vector<Outgoing>& batch) {
  serial_only("take_datagrams");
  for (Outgoing& o : batch) {
    if (lane_.spare.size() >= kSpareDatagrams) break;
    lane_.spare.push_back(std::move(o));
  }
  batch.clear();
  std::swap(batch, lane_.out);
}
std::vector<ServerEvent> ServerEndpoint::take_events() {
  serial_only("take_events");
  return std::exchange(events_, {});
}
std::vector<PlayerInput> ServerEndpoint::take_inputs() {
  serial_only("take_inputs");
  return std::exchange(inputs_, {});
}
bool ServerEndpoint::send_chat(std::uint32_t player_id, const Chat& chat, std::uint64_t) {
  serial_only("send_chat");
  auto it = sessions_.find(player_id);
  if (it == sessions_.end() || !it->second.connected) return false;
  if (it->second.chats.pending() >= config_.max_pending_chats) {
    ++chat_dropped_;
    return false;
  }
  it->second.chats.push(chat);  // sent by the timers' next run, with the session's results
  return true;
}

std::vector<PlayerCommand> ServerEndpoint::take_commands() {
  serial_only("take_commands");
  return std::exchange(commands_, {});
}

namespace {
template <class S>
SessionInfo info_of(std::uint32_t id, const S& s) {
  return {id, s.name, s.address, s.connected, s.acks.rtt_ms(), s.snapshots.acked_tick(), s.encoding,
          s.rate_limited, s.room, s.spectator, s.seal.drops(), s.identity};
}
}  // namespace

std::vector<SessionInfo> ServerEndpoint::sessions() const {
  std::vector<SessionInfo> out;
  for (const auto& [id, s] : sessions_) out.push_back(info_of(id, s));
  return out;
}

std::vector<SessionInfo> ServerEndpoint::sessions_of_room(std::uint32_t room) const {
  std::vector<SessionInfo> out;
  for (const Session* s : members_of(room)) out.push_back(info_of(s->player_id, *s));
  return out;
}

std::optional<SessionInfo> ServerEndpoint::session_info(std::uint32_t player_id) const {
  const auto it = sessions_.find(player_id);
  if (it == sessions_.end()) return std::nullopt;
  return info_of(it->first, it->second);
}

std::vector<std::uint32_t> ServerEndpoint::connected_players() const {
  std::vector<std::uint32_t> out;
  for (const auto& [id, s] : sessions_)
    if (s.connected) out.push_back(id);
  return out;
}

}  // namespace fts::protocol
