// libFuzzer target: every byte string is a room's journal as --resume reads it. The
// reader (store::read_journal, server/store/journal_read.cpp) takes a room's directory, so
// each input is written there as segment files: the bytes up to a line "~~" are
// journal-000001.jsonl, the rest journal-000002.jsonl (the newer one, tried first); no
// such line, one segment. Properties: nothing escapes (a room that cannot be resumed is a
// message); a resumed room's state is at or after its checkpoint, its sessions are by
// player id, its damage names the segment; the state and the config go through their
// JSON (a checkpoint's, a header's) unchanged (the same match_hash); the room steps on.
// Built and run by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fts/room/match_config_json.hpp"
#include "fts/room/stepper.hpp"
#include "fuzz_check.hpp"
#include "store/journal.hpp"
#include "store/match_state_json.hpp"

using namespace fts;
using fuzz::check;
using fuzz::fail;

namespace {

// This process's room directory (removed at exit).
const std::filesystem::path& room_dir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/fts-fuzz-journal-XXXXXX";
    if (!::mkdtemp(pattern.data())) fail("mkdtemp " + pattern);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(room_dir(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) fail("cannot write " + path.string());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto& dir = room_dir();
  constexpr std::string_view kNext = "\n~~\n";
  const auto cut = bytes.find(kNext);
  const auto seg1 = dir / store::segment_name(1), seg2 = dir / store::segment_name(2);
  std::error_code ec;
  if (cut == std::string_view::npos) {
    write_file(seg1, bytes);
    std::filesystem::remove(seg2, ec);
  } else {
    write_file(seg1, bytes.substr(0, cut + 1));
    write_file(seg2, bytes.substr(cut + kNext.size()));
  }
  const std::size_t files = cut == std::string_view::npos ? 1 : 2;

  try {
    auto read = store::read_journal(dir);
    if (const auto* err = std::get_if<std::string>(&read)) {
      check(!err->empty(), "a refused room says why");
      return 0;
    }
    const store::ResumedRoom& r = std::get<store::ResumedRoom>(read);
    check(r.state.tick >= r.checkpoint_tick, "the resumed state is at or after its checkpoint");
    check(r.skipped.size() < files, "at most the newer segment is skipped");
    check(r.damage.empty() || r.damage.rfind("journal-", 0) == 0, "the damage names the segment");
    for (std::size_t i = 1; i < r.sessions.size(); ++i)
      check(r.sessions[i - 1].player < r.sessions[i].player, "sessions are by player id, once each");
    check(sim::validate(r.config).empty(), "the header's config is valid");

    // The header's config through its JSON.
    const nlohmann::json cfg = room::match_config_to_json(r.config);
    auto cfg_again = room::parse_match_config(cfg.dump());
    if (const auto* err = std::get_if<std::string>(&cfg_again)) fail("the config read back is refused: " + *err);
    check(room::match_config_to_json(std::get<sim::MatchConfig>(cfg_again)) == cfg, "the config is unchanged");

    // The resumed state as the next checkpoint: written and read back bit for bit.
    const std::uint64_t hash = sim::match_hash(r.state);
    auto state_again = store::match_state_from_json(nlohmann::json::parse(store::match_state_to_json(r.state).dump()),
                                                   sim::make_match(r.config, r.seed));
    if (const auto* err = std::get_if<std::string>(&state_again)) fail("the resumed state read back is refused: " + *err);
    check(sim::match_hash(std::get<sim::MatchState>(state_again)) == hash, "the state is unchanged through JSON");

    // The room plays on from there.
    room::RoomStepper stepper(r.state, r.event_seq);
    (void)stepper.step({});
    check(stepper.match().tick == r.state.tick + 1, "the resumed room steps");
  } catch (const std::exception& e) {
    fail(std::string("exception escaped: ") + e.what());
  }
  return 0;
}
