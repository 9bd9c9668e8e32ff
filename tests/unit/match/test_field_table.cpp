// The one field-table mechanism (issue 38, fts/sim/field_table.hpp): every table of the
// wire, the checkpoint, the match configuration and the state hash is checked at compile
// time with names_every_member(); these show that a table which forgets a member fails it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "fts/sim/config_fields.hpp"
#include "fts/sim/field_table.hpp"
#include "fts/sim/match.hpp"

namespace {

using fts::fields::field;
using fts::fields::member_count;
using fts::fields::names_every_member;
using fts::fields::Skip;

struct Probe {
  int a = 0;
  double b = 0;
  std::string c;
  std::optional<int> d;
  std::vector<int> e;
};

struct K {};  // any kind: the check looks at the members only

constexpr auto kAll = std::make_tuple(field("a", &Probe::a, K{}), field("b", &Probe::b, K{}),
                                      field("c", &Probe::c, K{}), field("d", &Probe::d, K{}),
                                      field("e", &Probe::e, Skip{}));
constexpr auto kForgetsE = std::make_tuple(field("a", &Probe::a, K{}), field("b", &Probe::b, K{}),
                                           field("c", &Probe::c, K{}), field("d", &Probe::d, K{}));
// Five rows, but two over one member: still one member forgotten.
constexpr auto kTwiceA = std::make_tuple(field("a", &Probe::a, K{}), field("a2", &Probe::a, K{}),
                                         field("b", &Probe::b, K{}), field("c", &Probe::c, K{}),
                                         field("d", &Probe::d, K{}));

static_assert(member_count<Probe>() == 5);
static_assert(names_every_member<Probe>(kAll));
static_assert(!names_every_member<Probe>(kForgetsE));
static_assert(!names_every_member<Probe>(kTwiceA));
static_assert(names_every_member<Probe>(kForgetsE, &Probe::e));  // left out, on purpose

// The match configuration's table itself is checked where it is defined
// (common/src/config_fields.cpp): the check costs about 7 s of compile for 105 rows, so it
// runs once, not in every file that could.
constexpr auto kConfigFields = fts::sim::kMatchConfigFields;
constexpr std::size_t kConfigRows = std::tuple_size_v<decltype(kConfigFields)>;

}  // namespace

TEST_CASE("Field table: a table that forgets a member of its struct fails the check", "[fields]") {
  CHECK(names_every_member<Probe>(kAll));
  CHECK_FALSE(names_every_member<Probe>(kForgetsE));
  CHECK_FALSE(names_every_member<Probe>(kTwiceA));
  CHECK(member_count<fts::sim::MatchConfig>() == kConfigRows);
  CHECK(member_count<fts::sim::MatchState>() == 15);  // the hash's and the checkpoint's tables name 15
}

TEST_CASE("Field table: the config table names each key once", "[fields]") {
  std::vector<std::string> keys;
  fts::fields::for_each(kConfigFields, [&](const auto& row) { keys.emplace_back(row.key); });
  std::sort(keys.begin(), keys.end());
  CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  CHECK(keys.size() == kConfigRows);
}
