// One client's session on the server (server_session.hpp): what its datagrams do to it,
// their headers and seals.
#include "fts/protocol/server_session.hpp"

#include <algorithm>

#include "control_tables.hpp"
#include "fts/protocol/constants.hpp"
#include "fts/protocol/server.hpp"
#include "fts/sim/items.hpp"

namespace fts::protocol {

namespace {

// Why a command whose field did not read is not applied (PROTOCOL.md 4.6): op and item have
// their own codes (the same as an unknown op or item); any other field is "field". The ops
// and shop keys it lists are the wire's (control_tables.hpp) and the shop's (sim::item_table).
std::pair<ResultCode, std::string> fault_answer(const std::string& fault) {
  const ResultCode code = fault == "op" ? ResultCode::op : fault == "item" ? ResultCode::item : ResultCode::field;
  std::string why;
  if (fault == "op") {
    std::vector<std::string_view> ops;
    for (const char* name : wire::kCommandOpNames)
      if (name != std::string_view("unknown")) ops.push_back(name);
    why = "op must be text: ";
    for (std::size_t i = 0; i < ops.size(); ++i)
      why.append(i == 0 ? "" : i + 1 == ops.size() ? " or " : ", ").append(ops[i]);
  } else if (fault == "item") {
    why = "item must be one printable character:";
    for (const sim::ItemDef& item : sim::item_table()) why.append(" ").push_back(item.key);
  } else if (fault == "text") {
    why = "text must be text of at most " + std::to_string(kMaxTextBytes) + " bytes";
  } else {
    why = fault + " is not valid";
  }
  return {code, "command not applied: " + why};
}

}  // namespace

void ServerSession::apply(const Decoded<Datagram>& opened, std::uint64_t now_ms, const ServerConfig& config,
                          Applied& out, RejectCounters& rejects) {
  if (!opened) return rejects.add(opened.error());
  if (!datagrams.take(now_ms)) {
    ++rate_limited;
    return rejects.add(Reject::rate_limited);
  }
  const Datagram& d = *opened;
  // Validate every message before any state changes.
  for (const auto& m : d.messages) {
    if (!std::holds_alternative<Input>(m) && !std::holds_alternative<Command>(m) &&
        !std::holds_alternative<Ping>(m) && !std::holds_alternative<Bye>(m))
      return rejects.add(Reject::unexpected);
  }
  acked_scratch.clear();
  if (!acks.on_receive(d.header, now_ms, acked_scratch)) return rejects.add(Reject::stale);
  last_receive_ms = now_ms;
  for (auto seq : acked_scratch) {
    results.on_acked(seq);
    chats.on_acked(seq);
  }
  auto end = [&](Applied::End how, std::string why) {
    out.end = how;
    out.why = std::move(why);
  };
  for (const auto& m : d.messages) {
    if (const auto* in = std::get_if<Input>(&m)) {
      snapshots.on_ack(in->snapshot_ack);
      if (spectator) continue;  // a spectator's input is its heartbeat and acks, nothing more
      // Clients send their frames newest first (ClientEndpoint::send_input's message):
      // read backwards they are in order, with no copy; any other order is sorted so.
      const auto older = [](const InputFrame& a, const InputFrame& b) { return a.seq < b.seq; };
      const std::vector<InputFrame>* frames = &in->frames;
      std::vector<InputFrame> sorted;
      if (!std::is_sorted(frames->rbegin(), frames->rend(), older)) {
        sorted = in->frames;
        std::sort(sorted.rbegin(), sorted.rend(), older);
        frames = &sorted;
      }
      for (auto f = frames->rbegin(); f != frames->rend(); ++f) take_frame(*f, now_ms, config, out, rejects);
    } else if (const auto* c = std::get_if<Command>(&m)) {
      // rid 0 names no place in the reliable order: that message alone is dropped.
      if (c->rid == 0) {
        rejects.add(Reject::out_of_range);
        continue;
      }
      if (auto why = commands.accept(*c)) rejects.add(*why);
      for (auto& cmd : commands.take()) {
        ++unanswered;
        last_active_ms = now_ms;
        played = true;
        if (cmd.fault.empty()) {
          out.commands.push_back({player_id, room, cmd});
          continue;
        }
        // A field that did not read: answered here, never applied (PROTOCOL.md 4.6).
        rejects.add(Reject::bad_field);
        auto [code, text] = fault_answer(cmd.fault);
        if (!answer(cmd.rid, code, std::move(text), config.max_pending_results)) return end(Applied::End::overflow, "results");
      }
      if (commands.buffered() + unanswered > config.max_pending_commands) return end(Applied::End::overflow, "commands");
    } else if (const auto* bye = std::get_if<Bye>(&m)) {
      return end(Applied::End::bye, bye->reason);
    }
  }
}

void ServerSession::take_frame(const InputFrame& f, std::uint64_t now_ms, const ServerConfig& config, Applied& out,
                               RejectCounters& rejects) {
  if (f.seq <= last_input_seq) return;
  // A frame far ahead of the last one applied is not from an honest client (one frame per
  // tick): ignored, so it cannot make the real frames look old.
  if (f.seq - last_input_seq > config.max_input_lead) return rejects.add(Reject::out_of_range);
  last_input_seq = f.seq;
  out.inputs.push_back({player_id, room, f});
  if (f.move_x != 0 || f.move_y != 0 || f.fire) {
    last_active_ms = now_ms;
    played = true;
  }
}

bool ServerSession::answer(std::uint32_t rid, ResultCode code, std::string message, std::size_t max_pending) {
  wire::Text{0, kMaxTextBytes}.clamp(message);  // as the result's msg field reads (control_tables.hpp)
  if (unanswered > 0) --unanswered;
  results.push(Result{0, rid, code == ResultCode::ok, std::string(to_string(code)), std::move(message)});
  return results.pending() <= max_pending;
}

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

ServerSession* session_for(ServerSession* found, const Address& from, RejectCounters& rejects) {
  if (found == nullptr) {
    rejects.add(Reject::unknown_session);
    return nullptr;
  }
  if (found->address != from) {
    rejects.add(Reject::address_mismatch);
    return nullptr;
  }
  if (!found->connected) {
    rejects.add(Reject::unknown_session);
    return nullptr;
  }
  return found;
}

ServerSession* SessionTable::at_address(const Address& address) {
  const auto it = by_address_.find(address);
  return it == by_address_.end() ? nullptr : it->second;
}

ServerSession* SessionTable::with_session_id(std::uint32_t id) { return by_session_id_.find(id); }

void SessionTable::index(ServerSession& s) {
  ++generation_;
  by_session_id_.set(s.session_id, &s);
  by_address_[s.address] = &s;
}

void SessionTable::unindex(const ServerSession& s) {
  ++generation_;
  // Only the session's own entries: another session may hold the address by now.
  if (by_session_id_.find(s.session_id) == &s) by_session_id_.erase(s.session_id);
  if (auto it = by_address_.find(s.address); it != by_address_.end() && it->second == &s)
    by_address_.erase(it);
}

std::uint32_t SessionTable::next_player_id() {
  // Ids are never reused nor given where a room from another server took them; when they
  // run out (2^32 - 2 sessions in one process life) nobody new is taken.
  while (next_player_id_ != kNoPlayerIdLeft && taken_player_ids_.erase(next_player_id_) != 0)
    reserve_player_ids(next_player_id_);
  return next_player_id_;
}

}  // namespace fts::protocol
