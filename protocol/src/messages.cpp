// nlohmann mapping of the handshake and control messages (snapshots: snapshot_msg.cpp).
#include <string_view>

#include "mapping.hpp"

namespace fts::protocol {

using nlohmann::json;
using namespace detail;

namespace {
constexpr std::size_t kTokenHex = 32;
constexpr std::size_t kCookieHex = 48;
constexpr std::size_t kSealedTokenHex = 96;
constexpr std::size_t kKeyHex = 64;
constexpr std::size_t kNonceHex = 16;

const char* op_name(CommandOp op) {
  switch (op) {
    case CommandOp::buy: return "buy";
    case CommandOp::ready: return "ready";
    case CommandOp::play_again: return "again";
    case CommandOp::unknown: return "unknown";
    case CommandOp::chat: return "chat";
    case CommandOp::rooms: return "rooms";
  }
  return "?";
}
}  // namespace

void to_json(json& j, const Hello& m) {
  j = json{{"name", m.name}, {"token", m.token}, {"cookie", m.cookie}, {"pad", m.pad}, {"nonce", m.nonce}};
  if (!m.join.empty()) j["join"] = m.join;
  if (!m.room.empty()) j["room"] = m.room;
  if (!m.key.empty()) j["key"] = m.key;
}
void from_json(const json& j, Hello& m) {
  // Any string up to kMaxTextBytes: the server checks the name itself, so that a bad one
  // gets an answer that says what is wrong instead of a silent drop.
  const json& name = field(j, "name");
  if (!name.is_string()) fail(Reject::garbage);
  m.name = name.get<std::string>();
  if (m.name.size() > kMaxTextBytes) fail(Reject::out_of_range);
  m.nonce = as_hex(field(j, "nonce"), kNonceHex);
  if (m.nonce.empty()) fail(Reject::out_of_range);
  m.token = as_hex(field(j, "token"), kSealedTokenHex);
  m.cookie = as_hex(field(j, "cookie"), kCookieHex);
  m.pad = as_text(field(j, "pad"), kMaxDatagramBytes);
  // Optional (older clients send neither); the server checks the values and answers a
  // bad one with an error that says what is wrong.
  m.join = m.room = "";
  if (const json* join = optional_field(j, "join")) m.join = as_text(*join, 16);
  if (const json* room = optional_field(j, "room")) m.room = as_text(*room, 16);
  m.key = "";
  if (const json* key = optional_field(j, "key")) m.key = as_hex(*key, kKeyHex);
}

void to_json(json& j, const Challenge& m) { j = json{{"cookie", m.cookie}, {"key", m.key}}; }
void from_json(const json& j, Challenge& m) {
  m.cookie = as_hex(field(j, "cookie"), kCookieHex);
  m.key = as_hex(field(j, "key"), kKeyHex);
  if (m.cookie.empty() || m.key.empty()) fail(Reject::out_of_range);
}

void to_json(json& j, const Welcome& m) {
  j = json{{"player_id", m.player_id},
           {"token", m.token},
           {"tick_rate_hz", m.tick_rate_hz},
           {"snapshot_rate_hz", m.snapshot_rate_hz},
           {"arena_width_u", m.arena_width_u},
           {"arena_height_u", m.arena_height_u},
           {"max_players", m.max_players},
           {"timeout_ms", m.timeout_ms},
           {"reconnect_window_ms", m.reconnect_window_ms},
           {"input_redundancy", m.input_redundancy},
           {"server_tick", m.server_tick},
           {"reconnected", m.reconnected},
           {"frame_s", m.shop.frame_s},
           {"multiplier_upgrade_factor", m.shop.multiplier_upgrade_factor},
           {"bank_interest_factor", m.shop.bank_interest_factor}};
  if (!m.room.empty()) j["room"] = m.room;
  if (m.spectator) j["spectator"] = true;
}
void from_json(const json& j, Welcome& m) {
  m.player_id = as_u32(field(j, "player_id"));
  if (m.player_id == 0) fail(Reject::out_of_range);
  m.token = as_hex(field(j, "token"), kTokenHex);
  m.tick_rate_hz = as_u32(field(j, "tick_rate_hz"), 10000);
  m.snapshot_rate_hz = as_u32(field(j, "snapshot_rate_hz"), 10000);
  m.arena_width_u = as_double(field(j, "arena_width_u"), 0, 1e6);
  m.arena_height_u = as_double(field(j, "arena_height_u"), 0, 1e6);
  m.max_players = as_u32(field(j, "max_players"), 64);
  m.timeout_ms = as_u32(field(j, "timeout_ms"));
  m.reconnect_window_ms = as_u32(field(j, "reconnect_window_ms"));
  m.input_redundancy = as_u32(field(j, "input_redundancy"), kMaxInputFrames);
  m.server_tick = as_u32(field(j, "server_tick"));
  m.reconnected = as_bool(field(j, "reconnected"));
  m.shop.frame_s = as_double(field(j, "frame_s"), 1e-6, 1e6);
  m.shop.multiplier_upgrade_factor = as_double(field(j, "multiplier_upgrade_factor"), 0, 1e6);
  m.shop.bank_interest_factor = as_double(field(j, "bank_interest_factor"), 0, 1e6);
  m.room.clear();
  m.spectator = false;
  if (const json* room = optional_field(j, "room")) m.room = as_text(*room, 16);
  if (const json* spectator = optional_field(j, "spectator")) m.spectator = as_bool(*spectator);
}

void to_json(json& j, const Error& m) { j = json{{"code", m.code}, {"msg", m.message}}; }
void from_json(const json& j, Error& m) {
  m.code = as_text(field(j, "code"), 32);
  m.message = as_text(field(j, "msg"), kMaxTextBytes);
}

void to_json(json& j, const Input& m) {
  json frames = json::array();
  for (const auto& f : m.frames) frames.push_back(json::array({f.seq, f.move_x, f.move_y, f.fire ? 1 : 0}));
  j = json{{"ack", m.snapshot_ack}, {"f", std::move(frames)}};
}
void from_json(const json& j, Input& m) {
  m.snapshot_ack = as_u32(field(j, "ack"));
  m.frames.clear();
  for (const auto& f : as_array(field(j, "f"), kMaxInputFrames)) {
    if (!f.is_array() || f.size() != 4) fail(Reject::garbage);
    InputFrame frame;
    frame.seq = as_u32(f[0]);
    frame.move_x = static_cast<std::int8_t>(as_int(f[1], -1, 1));
    frame.move_y = static_cast<std::int8_t>(as_int(f[2], -1, 1));
    frame.fire = as_int(f[3], 0, 1) == 1;
    m.frames.push_back(frame);
  }
}

void to_json(json& j, const Command& m) {
  j = json{{"rid", m.rid}, {"op", op_name(m.op)}};
  if (m.op == CommandOp::buy && m.item != 0) j["item"] = std::string(1, m.item);
  if (m.op == CommandOp::chat) j["text"] = m.text;
}
// Lenient on purpose: a command the server cannot apply (unknown op, unknown or missing
// item) still decodes, so that it is consumed and answered with its result code instead
// of blocking the reliable channel; only its shape (rid, text fields) must be right.
void from_json(const json& j, Command& m) {
  m.rid = as_u32(field(j, "rid"));
  const std::string op = as_text(field(j, "op"), kMaxTextBytes);
  m.item = 0;
  if (op == "buy") {
    m.op = CommandOp::buy;
    if (const json* item = optional_field(j, "item")) {
      const std::string key = as_text(*item, kMaxTextBytes);
      if (key.size() == 1) m.item = key[0];
    }
  } else if (op == "ready") {
    m.op = CommandOp::ready;
  } else if (op == "again") {
    m.op = CommandOp::play_again;
  } else if (op == "chat") {
    m.op = CommandOp::chat;
    if (const json* text = optional_field(j, "text")) m.text = as_text(*text, kMaxTextBytes);
  } else if (op == "rooms") {
    m.op = CommandOp::rooms;
  } else {
    m.op = CommandOp::unknown;
  }
}

void to_json(json& j, const Result& m) {
  j = json{{"rid", m.rid}, {"cmd", m.command_rid}, {"ok", m.ok}, {"code", m.code}, {"msg", m.message}};
}
void from_json(const json& j, Result& m) {
  m.rid = as_u32(field(j, "rid"));
  if (m.rid == 0) fail(Reject::out_of_range);
  m.command_rid = as_u32(field(j, "cmd"));
  m.ok = as_bool(field(j, "ok"));
  m.code = as_text(field(j, "code"), 32);
  m.message = as_text(field(j, "msg"), kMaxTextBytes);
}

void to_json(json& j, const Chat& m) {
  j = json{{"rid", m.rid}, {"from", m.from}, {"name", m.name}, {"text", m.text}};
}
void from_json(const json& j, Chat& m) {
  m.rid = as_u32(field(j, "rid"));
  if (m.rid == 0) fail(Reject::out_of_range);
  m.from = as_u32(field(j, "from"));
  m.name = as_text(field(j, "name"), kMaxNameBytes);
  m.text = as_text(field(j, "text"), kMaxTextBytes);
}

void to_json(json& j, const Ping&) { j = json::object(); }
void from_json(const json& j, Ping&) {
  if (!j.is_object()) fail(Reject::garbage);
}

void to_json(json& j, const Bye& m) { j = json{{"reason", m.reason}}; }
void from_json(const json& j, Bye& m) { m.reason = as_text(field(j, "reason"), kMaxTextBytes); }

namespace {
struct TypeName {
  const char* operator()(const Hello&) const { return "hello"; }
  const char* operator()(const Challenge&) const { return "challenge"; }
  const char* operator()(const Welcome&) const { return "welcome"; }
  const char* operator()(const Error&) const { return "error"; }
  const char* operator()(const Input&) const { return "input"; }
  const char* operator()(const Command&) const { return "cmd"; }
  const char* operator()(const Result&) const { return "result"; }
  const char* operator()(const Ping&) const { return "ping"; }
  const char* operator()(const Bye&) const { return "bye"; }
  const char* operator()(const SnapshotMsg&) const { return "snap"; }
  const char* operator()(const Chat&) const { return "chat"; }
};

template <class T>
Message parse_as(const json& j) {
  T m;
  from_json(j, m);
  return m;
}
}  // namespace

std::string name_problem(const std::string& name) {
  if (name.empty()) return "a name needs at least one character";
  if (name.size() > kMaxNameBytes)
    return "a name has at most " + std::to_string(kMaxNameBytes) + " characters, this one " +
           std::to_string(name.size());
  for (unsigned char c : name)
    if (c < 0x20 || c > 0x7E) return "a name may only hold printable ASCII characters (no control codes, no accents)";
  return "";
}

const char* message_type(const Message& message) { return std::visit(TypeName{}, message); }

json message_to_json(const Message& m) {
  json j;
  std::visit([&j](const auto& msg) { to_json(j, msg); }, m);
  j["t"] = message_type(m);  // objects keep their keys sorted; "t" is just one of them
  return j;
}

Message message_from_json(const json& j) {
  const json& t = field(j, "t");
  if (!t.is_string()) fail(Reject::garbage);
  const std::string_view type = t.get_ref<const std::string&>();
  if (type == "hello") return parse_as<Hello>(j);
  if (type == "challenge") return parse_as<Challenge>(j);
  if (type == "welcome") return parse_as<Welcome>(j);
  if (type == "error") return parse_as<Error>(j);
  if (type == "input") return parse_as<Input>(j);
  if (type == "cmd") return parse_as<Command>(j);
  if (type == "result") return parse_as<Result>(j);
  if (type == "ping") return parse_as<Ping>(j);
  if (type == "bye") return parse_as<Bye>(j);
  if (type == "snap") return parse_as<SnapshotMsg>(j);
  if (type == "chat") return parse_as<Chat>(j);
  fail(Reject::unknown_type);
}

}  // namespace fts::protocol
