// The option table (common/cli): one row per member drives the command line, the
// environment, --help and the Markdown reference; a member without a row does not build.
#include <catch2/catch.hpp>

#include <map>

#include "fts/cli/option_table.hpp"

using namespace fts;

namespace {

struct Toy {
  std::uint32_t rate = 20;
  std::string mode = "fast";
  double scale = 1.5;
  std::string path;
  bool verbose = false;
  bool colour = true;
  std::optional<int> delay;
};

using cli::Int;
inline constexpr auto kToyTable = std::tuple{
    cli::value("--rate", "TOY_RATE", &Toy::rate, Int<std::uint32_t>{1, 100}, "must be 1..100 Hz", "ticks a second", "HZ"),
    cli::value("--mode", "TOY_MODE", &Toy::mode, cli::OneOf{{"fast", "slow"}}, "must be fast or slow", "how", "MODE"),
    cli::value("--scale", "", &Toy::scale, cli::Real{0.5, 4}, "must be 0.5..4", "size", "X"),
    cli::value("--path", "TOY_PATH", &Toy::path, cli::Text{true}, "must be a path", "where | what", "PATH"),
    cli::on("--verbose", "TOY_VERBOSE", &Toy::verbose, "say more"),
    cli::off("--no-colour", &Toy::colour, "no colours"),
    cli::value("--delay", "", &Toy::delay, cli::Maybe<Int<int>>{{0, 2000}}, "is 0..2000", "fixed delay (ms)", "MS"),
};
static_assert(fields::names_every_member<Toy>(kToyTable), "every member of Toy has a row");
// A table that forgets one member fails the same check (a program's static_assert).
inline constexpr auto kToyMissing = std::tuple{std::get<0>(kToyTable), std::get<1>(kToyTable)};
static_assert(!fields::names_every_member<Toy>(kToyMissing));

constexpr cli::Program kToy{"toy", "usage: toy [options]\n", "Toy's about text.\n", cli::Wording{true, "\""}, true, false};
constexpr cli::Program kPlain{"plain", "usage: plain [options] FILE\n", "", cli::Wording{false, "'"}, false, true};

cli::EnvLookup env_of(std::map<std::string, std::string> vars) {
  return [vars](const std::string& k) -> std::optional<std::string> {
    auto it = vars.find(k);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}

std::variant<Toy, std::string> parse_toy(const cli::Program& p, std::vector<std::string> args,
                                         std::map<std::string, std::string> env = {}) {
  Toy t;
  auto r = cli::parse(p, kToyTable, t, args, env_of(std::move(env)));
  if (auto* e = std::get_if<cli::Error>(&r)) return e->message;
  return t;
}

Toy toy(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = parse_toy(kToy, std::move(args), std::move(env));
  if (auto* e = std::get_if<std::string>(&r)) FAIL(*e);
  return std::get<Toy>(r);
}

std::string error(const cli::Program& p, std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = parse_toy(p, std::move(args), std::move(env));
  return std::holds_alternative<std::string>(r) ? std::get<std::string>(r) : "ok";
}

}  // namespace

TEST_CASE("Option table: defaults are the struct's, flags win over variables", "[cli]") {
  const Toy d = toy({});
  CHECK(d.rate == 20);
  CHECK(d.mode == "fast");
  CHECK_FALSE(d.delay.has_value());
  CHECK(toy({"--rate", "50"}).rate == 50);
  CHECK(toy({"--rate=51"}).rate == 51);
  CHECK(toy({"--rate", "5", "--rate", "6"}).rate == 6);  // the last one wins
  CHECK(toy({}, {{"TOY_RATE", "70"}}).rate == 70);
  CHECK(toy({"--rate", "80"}, {{"TOY_RATE", "70"}}).rate == 80);
  CHECK(toy({}, {{"TOY_VERBOSE", "1"}}).verbose);
  CHECK_FALSE(toy({}, {{"TOY_VERBOSE", "0"}}).verbose);
  CHECK(toy({"--verbose"}).verbose);
  CHECK_FALSE(toy({"--no-colour"}).colour);
  CHECK(toy({"--delay", "40"}).delay == 40);
  CHECK(toy({"--scale", "2.25"}).scale == 2.25);
}

TEST_CASE("Option table: a program that reads no variables ignores them", "[cli]") {
  Toy t;
  auto r = cli::parse(kPlain, kToyTable, t, {"in.json"}, env_of({{"TOY_RATE", "70"}}));
  REQUIRE(std::holds_alternative<cli::Parsed>(r));
  CHECK(t.rate == 20);
  CHECK(std::get<cli::Parsed>(r).rest == std::vector<std::string>{"in.json"});
}

TEST_CASE("Option table: refusals name the flag or variable, the rule and the value", "[cli]") {
  CHECK(error(kToy, {"--rate", "0"}) == R"(--rate: must be 1..100 Hz, got "0")");
  CHECK(error(kToy, {"--rate", "1e3"}) == R"(--rate: must be 1..100 Hz, got "1e3")");
  CHECK(error(kToy, {"--rate", "-1"}) == R"(--rate: must be 1..100 Hz, got "-1")");
  CHECK(error(kToy, {}, {{"TOY_RATE", "101"}}) == R"(TOY_RATE: must be 1..100 Hz, got "101")");
  CHECK(error(kToy, {"--mode", "medium"}) == R"(--mode: must be fast or slow, got "medium")");
  CHECK(error(kToy, {"--scale", "4.5"}) == R"(--scale: must be 0.5..4, got "4.5")");
  CHECK(error(kToy, {"--scale", "2x"}) == R"(--scale: must be 0.5..4, got "2x")");
  CHECK(error(kToy, {"--path", ""}) == R"(--path: must be a path, got "")");
  CHECK(error(kPlain, {"--delay", "3000"}) == "--delay is 0..2000, got '3000'");
  CHECK(error(kToy, {"--rate"}) == "--rate: needs a value");
  CHECK(error(kPlain, {"--rate"}) == "--rate needs HZ");
  CHECK(error(kToy, {"--colour=red"}) == "unknown flag --colour (see --help)");
  CHECK(error(kToy, {"stray"}) == R"(unexpected argument "stray" (see --help))");
}

TEST_CASE("Option table: --help shows each row with its variable and default", "[cli]") {
  const std::string help = cli::help_text(kToy, cli::infos(kToyTable));
  CHECK_THAT(help, Catch::StartsWith("usage: toy [options]\n"));
  CHECK_THAT(help, Catch::Contains("  --rate HZ                   ticks a second [TOY_RATE, default 20]\n"));
  CHECK_THAT(help, Catch::Contains("  --scale X                   size [default 1.5]\n"));
  CHECK_THAT(help, Catch::Contains("  --verbose                   say more [TOY_VERBOSE=1]\n"));
  CHECK_THAT(help, Catch::Contains("  --path PATH                 where | what [TOY_PATH]\n"));
  CHECK_THAT(help, Catch::Contains("-h, --help"));
  CHECK_THAT(help, Catch::EndsWith("Toy's about text.\n"));
  Toy t;
  auto r = cli::parse(kToy, kToyTable, t, {"-h"});
  REQUIRE(std::holds_alternative<cli::Parsed>(r));
  CHECK(std::get<cli::Parsed>(r).help);
  r = cli::parse(kToy, kToyTable, t, {"--help-markdown"});
  CHECK(std::get<cli::Parsed>(r).markdown);
}

TEST_CASE("Option table: the Markdown reference has a row per flag", "[cli]") {
  const std::string md = cli::markdown(kToy, cli::infos(kToyTable), "toy");
  CHECK_THAT(md, Catch::StartsWith("## toy\n\n```\nusage: toy [options]\n```\n\n"));
  CHECK_THAT(md, Catch::Contains("| flag | environment | default | values | meaning |\n"));
  CHECK_THAT(md, Catch::Contains("| `--rate HZ` | `TOY_RATE` | `20` | 1..100 | ticks a second |\n"));
  CHECK_THAT(md, Catch::Contains("| `--mode MODE` | `TOY_MODE` | `fast` | fast, slow | how |\n"));
  CHECK_THAT(md, Catch::Contains("| `--path PATH` | `TOY_PATH` | (none) | text | where \\| what |\n"));
  CHECK_THAT(md, Catch::Contains("| `--verbose` | `TOY_VERBOSE=1` | off |  | say more |\n"));
  CHECK_THAT(md, Catch::Contains("| `--no-colour` | | on |  | no colours |\n"));
  CHECK_THAT(md, Catch::Contains("| `--delay MS` | | (none) | 0..2000 | fixed delay (ms) |\n"));
  const std::string plain = cli::markdown(kPlain, cli::infos(kToyTable), "plain");
  CHECK_THAT(plain, Catch::Contains("| flag | default | values | meaning |\n"));
  CHECK_THAT(plain, Catch::Contains("| `--rate HZ` | `20` | 1..100 | ticks a second |\n"));
}
