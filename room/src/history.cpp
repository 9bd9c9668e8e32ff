// The history reader of journals (fts/room/record.hpp): a journal that keeps every segment
// read into a tape, as a record file is. The checkpoints are not read back (their hash is
// checked against the replay instead): the tape starts from make_match(config, seed).
#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "fts/room/json_fields.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/record.hpp"
#include "fts/room/text.hpp"

namespace fts::room {
namespace {

using nlohmann::json;

std::string dump_head(const json& head) { return head.contains("config") ? head.at("config").dump() : ""; }

// Reads one segment's lines into the tape; "" or what is wrong, naming the line.
std::string read_segment(std::istream& in, const std::string& file, bool first, bool last, Tape& t, json& first_head,
                         std::size_t& lines, std::size_t max_lines) {
  std::string line, why;
  for (std::size_t no = 1; std::getline(in, line); ++no) {
    const std::string where = file + " line " + std::to_string(no) + ": ";
    if (++lines > max_lines) return "the history has more than " + std::to_string(max_lines) + " lines";
    // A line without its end: a crash's; the history ends before it (only in the newest segment).
    if (in.eof()) return last ? std::string() : where + "torn (no end of line) in a segment that is not the last";
    auto j = parse_json(line, why);
    if (!j) return where + "invalid JSON: " + why;
    try {
      if (no == 1) {
        if (!j->contains("fts_journal") || !j->at("fts_journal").is_number_integer() ||
            j->at("fts_journal").get<std::int64_t>() != kJournalFormat)
          return where + "not a journal segment header of format " + std::to_string(kJournalFormat);
        if (first) {
          first_head = *j;
          if (!j->at("seed").is_number_unsigned()) return where + "seed must be a non-negative integer";
          t.seed = j->at("seed").get<std::uint64_t>();
          auto cfg = parse_match_config(j->at("config").dump());
          if (auto* err = std::get_if<std::string>(&cfg)) return where + "config: " + *err;
          t.config = std::get<sim::MatchConfig>(cfg);
        } else if (j->at("seed") != first_head.at("seed") || dump_head(*j) != dump_head(first_head)) {
          return where + "another match's segment (its seed or config differs from the first segment's)";
        }
        continue;
      }
      if (j->contains("session") || j->contains("released")) continue;  // a resume's, not the match's
      if (first && no == 2 && j->at("tick").get<std::int64_t>() != 0)
        return where + "the first checkpoint is at tick " + j->at("tick").dump() +
               ", not 0: the journal does not hold the match from its start";
      // A checkpoint or hash line (its hash, its tick), or an input line.
      if (auto err = append_line(t, *j, no, file); !err.empty()) return where + err;
    } catch (const std::exception& e) {
      return where + e.what();
    }
  }
  return {};
}

std::variant<Tape, std::string> load_journal(const std::filesystem::path& dir, std::size_t max_lines) {
  const auto segments = list_segments(dir);
  if (segments.empty()) return "no journal segments (journal-NNNNNN.jsonl) in " + dir.string();
  if (segments.front().first != 1)
    return dir.string() + " starts at segment " + std::to_string(segments.front().first) +
           ": its first segments were removed (a resume journal keeps only the newest), so it does not hold the "
           "whole match";
  Tape t;
  t.format = "journal " + std::to_string(kJournalFormat);
  json first_head;
  std::size_t lines = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const auto& [n, path] = segments[i];
    if (n != i + 1) return dir.string() + ": segment " + std::to_string(i + 1) + " is missing";
    std::ifstream in(path);
    const std::string file = path.filename().string();
    if (!in) return file + ": cannot read";
    if (auto err = read_segment(in, file, i == 0, i + 1 == segments.size(), t, first_head, lines, max_lines);
        !err.empty())
      return err;
  }
  return t;
}

}  // namespace

std::string segment_name(std::uint64_t n) {
  std::string digits = std::to_string(n);
  if (digits.size() < 6) digits.insert(0, 6 - digits.size(), '0');
  return "journal-" + digits + ".jsonl";
}

std::vector<std::pair<std::uint64_t, std::filesystem::path>> list_segments(const std::filesystem::path& dir) {
  std::vector<std::pair<std::uint64_t, std::filesystem::path>> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    constexpr std::string_view prefix = "journal-", suffix = ".jsonl";
    if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix)) continue;
    const auto n = to_integer(name.substr(prefix.size(), name.size() - prefix.size() - suffix.size()));
    if (n && *n > 0) out.emplace_back(static_cast<std::uint64_t>(*n), entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::variant<Tape, std::string> load_history(const std::filesystem::path& path, std::size_t max_lines) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return load_journal(path, max_lines);
  std::ifstream in(path);
  if (!in) return "cannot read " + path.string();
  return load_tape(in, max_lines);
}

std::variant<ReplayReport, std::string> replay_history(const std::filesystem::path& path) {
  auto loaded = load_history(path);
  if (auto* err = std::get_if<std::string>(&loaded)) return *err;
  return replay_tape(std::get<Tape>(loaded));
}

}  // namespace fts::room
