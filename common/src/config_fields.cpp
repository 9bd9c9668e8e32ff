#include "fts/sim/config_fields.hpp"

namespace fts::sim {

static_assert(fields::names_every_member<MatchConfig>(kMatchConfigFields),
              "kMatchConfigFields must have a row for every MatchConfig member");

MatchConfig client_part(const MatchConfig& cfg) {
  MatchConfig out;
  fields::for_each(kMatchConfigFields, [&](const auto& f) {
    if constexpr (is_client_key<decltype(f.kind)>) out.*f.member = cfg.*f.member;
  });
  return out;
}

}  // namespace fts::sim
