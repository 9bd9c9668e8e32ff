// The client predicts with the server's physics (issue 36): a tuned host's welcome
// carries every field of its configuration that config_fields.hpp marks CLIENT, the client
// reads back exactly the server's values for them (and the defaults for the rest), and
// its predictor, built from that welcome, lands where the tuned match puts the ball.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/snapshot_build.hpp"
#include "fts/sim/config_fields.hpp"
#include "fts/sim/match.hpp"
#include "fts/sim/match_view.hpp"
#include "predict/prediction.hpp"
#include "prediction_match.hpp"

using namespace fts;
using client::test::move;
using client::test::playing_alone;

namespace {

// Every CLIENT field moved off its default (numbers x0.97, integers +3, the model to
// another), and two host fields too: a host that tuned everything.
sim::MatchConfig tuned_everything() {
  const nlohmann::json defaults = room::match_config_to_json({});
  nlohmann::json j = nlohmann::json::object();
  for (const std::string& key : room::match_config_client_keys()) {
    const nlohmann::json& v = defaults.at(key);
    if (v.is_string()) j[key] = v == "discrete" ? "seed" : "discrete";
    else if (v.is_number_integer()) j[key] = v.get<std::int64_t>() + 3;
    else if (key == "tick_rate_hz") j[key] = 97;  // fts-server runs whole rates
    else j[key] = v.get<double>() * 0.97;
  }
  j["price_life"] = 7;
  j["spawn_protection_s"] = 1.5;
  auto parsed = room::parse_match_config(j.dump());
  if (auto* err = std::get_if<std::string>(&parsed)) FAIL(*err);
  return std::get<sim::MatchConfig>(parsed);
}

protocol::Welcome through_wire(const protocol::Welcome& w, protocol::Encoding enc) {
  protocol::Header h;
  h.encoding = enc;
  h.session = 7;
  auto d = protocol::decode_datagram(protocol::encode_datagram(h, {w}));
  REQUIRE(d.ok());
  REQUIRE(d->messages.size() == 1);
  return std::get<protocol::Welcome>(d->messages.at(0));
}

protocol::Welcome welcome_for(const sim::MatchConfig& cfg) {
  protocol::Welcome w;
  w.player_id = 1;
  w.token = std::string(32, 'a');
  w.match = sim::client_part(cfg);  // what make_endpoint_config() puts in every welcome
  return w;
}


// The largest distance between the predicted and the match's own ball over 80 ticks of
// thrusts and coasting (the inputs in force at their ticks, as the server applies them).
double worst_miss(sim::MatchState s, client::OwnBallPredictor p) {
  const auto base = client::test::snapshot_of(s);
  p.on_snapshot(base, 1, static_cast<double>(base.tick), 1000);
  const std::int64_t t0 = s.tick;
  const auto input_for = [&](std::int64_t t) {
    return t < t0 + 30 ? std::pair{1, 1} : t < t0 + 40 ? std::pair{-1, 0} : std::pair{0, 0};
  };
  for (std::int64_t t : {t0, t0 + 30, t0 + 40}) p.input(t, input_for(t).first, input_for(t).second);
  double worst = 0;
  for (int i = 0; i < 80; ++i) {
    const auto [dx, dy] = input_for(s.tick);
    sim::step(s, move(dx, dy));
    const sim::Ball* b = sim::find_ball(s.world, s.players[0].ball);
    const auto at = p.at(static_cast<double>(s.tick), 1000);
    REQUIRE(b != nullptr);
    REQUIRE(at.has_value());
    worst = std::max(worst, std::hypot(at->x - b->pos.x, at->y - b->pos.y));
  }
  return worst;
}

}  // namespace

TEST_CASE("Prediction config: a tuned host's welcome gives the client the server's value of every CLIENT field",
          "[client][predict][config]") {
  const sim::MatchConfig tuned = tuned_everything();
  const nlohmann::json server = room::match_config_to_json(tuned);
  const nlohmann::json defaults = room::match_config_to_json({});
  const auto client_keys = room::match_config_client_keys();
  REQUIRE(client_keys.size() >= 8);
  for (auto enc : {protocol::Encoding::json, protocol::Encoding::msgpack}) {
    const protocol::Welcome got = through_wire(welcome_for(tuned), enc);
    CHECK(got == welcome_for(tuned));
    const nlohmann::json client = room::match_config_to_json(got.match);
    for (const auto& [key, value] : server.items()) {
      const bool marked = std::find(client_keys.begin(), client_keys.end(), key) != client_keys.end();
      INFO(key << (marked ? " (client)" : " (host)") << (enc == protocol::Encoding::json ? " json" : " msgpack"));
      if (marked) {
        CHECK(value != defaults.at(key));  // tuned: a field the welcome dropped would show
        CHECK(client.at(key) == value);
      } else {
        CHECK(client.at(key) == defaults.at(key));  // the host's alone: not sent
      }
    }
    // What the shop screen states comes from the same fields.
    CHECK(got.shop() == sim::shop_terms(tuned));
    CHECK(got.tick_rate_hz() == 97);
  }
}

TEST_CASE("Prediction config: built from a tuned host's welcome, the predictor steps that host's match",
          "[client][predict][config]") {
  // The host of issue 36 (friction 0.95 per frame), and one that changed the model too.
  sim::MatchConfig issue;
  issue.friction_per_frame = 0.95;
  sim::MatchConfig other = issue;
  other.model = sim::Model::discrete;
  other.substeps = 3;
  other.friction_cutoff_u_per_s = 4.0;
  other.frame_s = 0.02;
  other.tick_rate_hz = 60;
  for (const sim::MatchConfig& cfg : {issue, other, tuned_everything()}) {
    const sim::MatchState s = playing_alone(cfg);
    for (auto enc : {protocol::Encoding::json, protocol::Encoding::msgpack}) {
      const protocol::Welcome w = through_wire(welcome_for(cfg), enc);
      // The base is quantized (1/16 u, 1/16 u/s): the rest is the same arithmetic.
      CHECK(worst_miss(s, client::OwnBallPredictor(w.match)) < 0.1);
    }
    // What the client did before: the default physics on the welcome's platform and
    // tick rate. Against these hosts it misses by far more (the test's teeth).
    sim::MatchConfig old;
    old.arena_width_u = cfg.arena_width_u;
    old.arena_height_u = cfg.arena_height_u;
    old.tick_rate_hz = cfg.tick_rate_hz;
    CHECK(worst_miss(s, client::OwnBallPredictor(old)) > 1.0);
  }
}

TEST_CASE("Prediction config: a welcome the step cannot run on predicts with the defaults, finitely",
          "[client][predict][config]") {
  sim::MatchConfig broken;
  broken.friction_per_frame = 0;  // the welcome's range lets it through; no valid config has it
  broken.frame_s = 0.003;         // a fractional exponent: the friction factor would be log(0)
  const sim::MatchState s = playing_alone({});
  CHECK(worst_miss(s, client::OwnBallPredictor(broken)) < 0.1);
}
