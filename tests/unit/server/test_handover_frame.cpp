// The hand-over channel's frames (issue 42, PROTOCOL.md 14): the test vector the document
// gives, what a frame opens under, and the fleet secret's file.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/handover_frame.hpp"

using namespace fts::server::handover;

namespace {

template <class C>
std::string hex(const C& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char b : bytes) {
    out += digits[b >> 4];
    out += digits[b & 15];
  }
  return out;
}

std::string counting(int from, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += static_cast<char>(from + i);
  return s;
}

Bytes challenge_of(int from) {
  const std::string s = counting(from, static_cast<int>(kChallengeBytes));
  return Bytes(s.begin(), s.end());
}

constexpr const char* kVectorKey = "cb2f5160fc1f7e05a55ef49d340b48da2e5a78099d53393351cd579dd42503d6";
constexpr const char* kVectorMac = "6305a730cb5e2ed8ac3106c8415213b9a89518837158c79cb84f879c7693ae70";
constexpr const char* kVectorConfirm = "274fe66cebdccd9f75d80169ac6b03ba7c8903190d761d041a6772d2501dee7e";

}  // namespace

TEST_CASE("Hand-over frames: the test vector of PROTOCOL.md 14", "[server][handover]") {
  const std::string key = key_of_secret(counting(0, 32));
  const auto m = mac(key, kRequestLabel, challenge_of(0x20), R"({"fts_handover":1})");
  CHECK(hex(key) == kVectorKey);
  CHECK(hex(m) == kVectorMac);
  const auto c = mac(key, kConfirmLabel, challenge_of(0x20), R"({"fts_handover_confirm":1,"rooms":["ABCDE"]})");
  CHECK(hex(c) == kVectorConfirm);
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(doc.find(std::string("key      ") + kVectorKey) != std::string::npos);
  CHECK(doc.find(std::string("request  ") + kVectorMac) != std::string::npos);
  CHECK(doc.find(std::string("confirm  ") + kVectorConfirm) != std::string::npos);
}

TEST_CASE("Hand-over frames: a frame opens only under its key, label and challenge", "[server][handover]") {
  const std::string key = key_of_secret(counting(1, 40));
  const Bytes challenge = challenge_of(7);
  const std::string json = R"({"ok":true,"port":7777})";
  const Bytes f = frame(key, kReplyLabel, challenge, json);
  REQUIRE(f.size() == 4 + json.size() + kMacBytes);
  CHECK(frame_length({f[0], f[1], f[2], f[3]}) == json.size());
  const Bytes body(f.begin() + 4, f.end());
  CHECK(open_body(key, kReplyLabel, challenge, body) == json);
  CHECK_FALSE(open_body(key, kRequestLabel, challenge, body));               // a reply is no request
  CHECK_FALSE(open_body(key, kReplyLabel, challenge_of(8), body));           // another connection's
  CHECK_FALSE(open_body(key_of_secret(counting(2, 40)), kReplyLabel, challenge, body));  // another secret
  Bytes tampered = body;
  tampered[3] ^= 1;
  CHECK_FALSE(open_body(key, kReplyLabel, challenge, tampered));
  CHECK_FALSE(open_body(key, kReplyLabel, challenge, Bytes(body.begin(), body.begin() + 10)));
}

TEST_CASE("Hand-over: the fleet secret's file is refused when short, shared or missing", "[server][handover]") {
  const auto dir = std::filesystem::temp_directory_path() / ("fts-secret-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& bytes, unsigned mode) {
    const auto path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    ::chmod(path.c_str(), mode);
    return path;
  };
  std::string why;
  CHECK(read_secret_file(write("short", counting(0, 31), 0600), why).empty());
  CHECK(why.find("holds 31 bytes; at least 32") != std::string::npos);
  why.clear();
  CHECK(read_secret_file(write("shared", counting(0, 32), 0644), why).empty());
  CHECK(why.find("read by others") != std::string::npos);
  why.clear();
  CHECK(read_secret_file((dir / "missing").string(), why).empty());
  CHECK(why.find("cannot read") != std::string::npos);
  why.clear();
  const std::string key = read_secret_file(write("good", counting(5, 48), 0600), why);
  CHECK(why.empty());
  CHECK(key == key_of_secret(counting(5, 48)));
  CHECK(key.size() == 32);
  std::filesystem::remove_all(dir);
}
