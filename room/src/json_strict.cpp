// parse_json (fts/room/json_fields.hpp): JSON from outside, read strictly. nlohmann keeps
// the last of two equal keys and says nothing, so a first pass walks the text with a SAX
// checker (no tree) that refuses a repeated key at any depth, or nesting past a bound;
// only text it passes is parsed into a tree. The parser's callback was the other way in,
// but nlohmann stops calling it inside a part it discarded, which loses the walk's place.
#include <set>
#include <string>
#include <vector>

#include "fts/room/json_fields.hpp"

namespace fts::room {
namespace {

using nlohmann::json;

// A key as an error shows it: printable ASCII ('?' for any other byte, so the message
// is clean text for a log or a reply), cut to a length a reply can carry.
std::string cut(const std::string& key) {
  constexpr std::size_t kMaxShown = 48;
  std::string out = key.substr(0, kMaxShown);
  for (char& c : out)
    if (c < 0x20 || c > 0x7e) c = '?';
  return key.size() > kMaxShown ? out + "..." : out;
}
std::string quoted_key(const std::string& key) { return json(cut(key)).dump(); }

class StrictChecker : public nlohmann::json_sax<json> {
 public:
  explicit StrictChecker(int max_depth) : max_depth_(max_depth) {}
  const std::string& why() const { return why_; }

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    Frame& f = frames_.back();
    f.key = k;
    if (f.keys.insert(k).second) return true;
    const std::string where = path();
    why_ = "key " + quoted_key(k) + " appears twice in one object" + (frames_.size() == 1 ? "" : " (at " + where + ")");
    return false;
  }

  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    why_ = e.what();
    return false;
  }

 private:
  struct Frame {
    bool object = false;
    std::set<std::string> keys;  // an object's keys so far
    std::string key;             // an object's current key
    std::size_t index = 0;       // an array's current element
  };

  bool open(bool object) {
    if (max_depth_ != kNoDepthLimit && static_cast<int>(frames_.size()) >= max_depth_) {
      why_ = "the text nests at most " + std::to_string(max_depth_) + " levels deep; this goes deeper (at " +
             (frames_.size() == 0 ? std::string("the top") : path()) + ")";
      return false;
    }
    frames_.push_back(Frame{object, {}, {}, 0});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  // A value ended: an array moves on to its next element.
  bool value() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return true;
  }
  // Where the walk is: keys and indices from the top, e.g. "rooms[2].code".
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_)
      p += f.object ? (p.empty() ? "" : ".") + cut(f.key) : "[" + std::to_string(f.index) + "]";
    return p;
  }

  int max_depth_;
  std::vector<Frame> frames_;
  std::string why_;
};

}  // namespace

std::optional<json> parse_json(const std::string& text, std::string& why, int max_depth) {
  StrictChecker checker(max_depth);
  if (!json::sax_parse(text, &checker)) {
    why = checker.why().empty() ? "not JSON" : checker.why();
    return std::nullopt;
  }
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // the checker passed it: not expected
    why = e.what();
    return std::nullopt;
  }
}

}  // namespace fts::room
