// One table of options per program (issue 38): each row names a flag, its environment
// variable (or none), the member of the program's options struct it sets, how its text
// is checked (a range, a list of names, a parser), the phrase a bad value is refused
// with, and one line of help. The default is the struct's member initialiser and nothing
// else: --help and the Markdown reference show it from a default-made struct.
//
// From the table come the command line (CLI11 underneath), the environment, the keys of
// a config file a row overrides, `--help` and `--help-markdown` (docs/flags/<program>.md,
// which a test holds to the program's output). A member with no row does not build:
//   static_assert(fts::fields::names_every_member<Options>(kTable, &Options::left_out...));
// (fts/sim/field_table.hpp; the rows name their member as `member`).
#pragma once

#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include "fts/sim/field_table.hpp"

namespace fts::cli {

// ---- checks: how a text becomes a member's value and how a value is shown ---------------

// A whole number lo..hi, decimal digits only.
template <class T>
struct Int {
  T lo, hi;
};
// A number lo..hi (strtod's forms, nothing after it).
struct Real {
  double lo, hi;
};
// Any text; with non_empty, any but "".
struct Text {
  bool non_empty = false;
};
// A std::string member: one of up to 8 names.
struct OneOf {
  std::array<std::string_view, 8> names{};
};
// Any member: a parser and a printer (an enum, an address, a port with words).
template <class T>
struct Custom {
  bool (*parse)(const std::string& text, T& out);
  std::string (*show)(const T& value);
  std::string_view values;  // the accepted values, for the reference ("on, off or 1..65535")
};
// A std::optional<T> member: unset unless given; the check is for the T inside.
template <class C>
struct Maybe {
  C inner;
};
// A bool member set by a flag without a value (Kind::on sets true, Kind::off false).
struct Switch {};

enum class Kind : std::uint8_t { value, on, off };

// ---- a row -------------------------------------------------------------------------------

// A config-file key the row's option overrides when given (fts-server's --config): the
// key, and what a value in the file that the option's check refuses is told.
struct ConfigKey {
  std::string_view key;
  std::string_view want;
};

template <class O, class T, class C>
struct Opt {
  std::string_view flag;  // "--port"
  std::string_view env;   // "FTS_PORT"; "": none
  T O::*member;
  C check;
  std::string_view want;        // a bad value is refused with: "must be 10..1000 Hz"
  std::string_view help;        // one line
  std::string_view value_name;  // "PORT" ("" for a switch)
  Kind kind = Kind::value;
  bool hidden = false;  // parsed, but in neither --help nor the reference
  ConfigKey config{};
};

template <class O, class T, class C>
constexpr Opt<O, T, C> value(std::string_view flag, std::string_view env, T O::*member, C check, std::string_view want,
                             std::string_view help, std::string_view value_name = "V") {
  return {flag, env, member, check, want, help, value_name};
}
template <class O>
constexpr Opt<O, bool, Switch> on(std::string_view flag, std::string_view env, bool O::*member, std::string_view help) {
  return {flag, env, member, Switch{}, "", help, "", Kind::on};
}
template <class O>
constexpr Opt<O, bool, Switch> off(std::string_view flag, bool O::*member, std::string_view help) {
  return {flag, "", member, Switch{}, "", help, "", Kind::off};
}
template <class Row>
constexpr Row hidden(Row row) {
  row.hidden = true;
  return row;
}
template <class Row>
constexpr Row overrides(Row row, std::string_view key, std::string_view want) {
  row.config = {key, want};
  return row;
}

// ---- parsing and showing one value -------------------------------------------------------

std::string show_real(double v);
bool parse_real(const std::string& text, double& out);

template <class T>
bool parse(const Int<T>& c, const std::string& text, T& out) {
  using Wide = std::conditional_t<std::is_signed_v<T>, std::int64_t, std::uint64_t>;
  Wide v = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end) return false;
  if (v < static_cast<Wide>(c.lo) || v > static_cast<Wide>(c.hi)) return false;
  out = static_cast<T>(v);
  return true;
}
template <class T>
std::string show(const Int<T>&, const T& v) {
  return std::to_string(v);
}
template <class T>
std::string values(const Int<T>& c) {
  return std::to_string(c.lo) + ".." + std::to_string(c.hi);
}

inline bool parse(const Real& c, const std::string& text, double& out) {
  double v = 0;
  if (!parse_real(text, v) || !(v >= c.lo && v <= c.hi)) return false;
  out = v;
  return true;
}
inline std::string show(const Real&, double v) { return show_real(v); }
inline std::string values(const Real& c) { return show_real(c.lo) + ".." + show_real(c.hi); }

inline bool parse(const Text& c, const std::string& text, std::string& out) {
  if (c.non_empty && text.empty()) return false;
  out = text;
  return true;
}
inline std::string show(const Text&, const std::string& v) { return v; }
inline std::string values(const Text& c) { return c.non_empty ? "text" : "text (may be empty)"; }

bool parse(const OneOf& c, const std::string& text, std::string& out);
inline std::string show(const OneOf&, const std::string& v) { return v; }
std::string values(const OneOf& c);

template <class T>
bool parse(const Custom<T>& c, const std::string& text, T& out) {
  return c.parse(text, out);
}
template <class T>
std::string show(const Custom<T>& c, const T& v) {
  return c.show(v);
}
template <class T>
std::string values(const Custom<T>& c) {
  return std::string(c.values);
}

template <class C, class T>
bool parse(const Maybe<C>& c, const std::string& text, std::optional<T>& out) {
  T v{};
  if (!parse(c.inner, text, v)) return false;
  out = v;
  return true;
}
template <class C, class T>
std::string show(const Maybe<C>& c, const std::optional<T>& v) {
  return v ? show(c.inner, *v) : "";
}
template <class C>
std::string values(const Maybe<C>& c) {
  return values(c.inner);
}

// A switch's variable: "1" is on, anything else off.
inline bool parse(const Switch&, const std::string& text, bool& out) {
  out = text == "1";
  return true;
}
inline std::string show(const Switch&, bool v) { return v ? "on" : "off"; }
inline std::string values(const Switch&) { return ""; }

// ---- the program ------------------------------------------------------------------------

// How a program words its refusals: fts-server `--port: must be ..., got "x"`, the others
// `--fps is 1..240, got 'x'` or `--count must be 1..256, got 0`.
struct Wording {
  bool colon = false;          // "--port: ..." rather than "--port ..."
  std::string_view quote = ""; // around a refused value
};

struct Program {
  std::string_view name;      // "fts-server"
  std::string_view synopsis;  // the usage lines at the top of --help
  std::string_view about;     // text after the options (controls, modes, exit codes)
  Wording wording;
  bool reads_env = false;     // rows' variables are read (fts-server)
  bool positional = false;    // arguments that are not flags are kept (fts-sim's scene)
};

// One row without its types: what the command line, the help and the reference need.
struct RowInfo {
  std::string flag, env, value_name, help, want, default_value, values;
  Kind kind = Kind::value;
  bool hidden = false;
  std::string config_key, config_want;
};

template <class O, class T, class C>
RowInfo info(const Opt<O, T, C>& row) {
  static const O defaults{};
  return {std::string(row.flag), std::string(row.env), std::string(row.value_name), std::string(row.help),
          std::string(row.want), show(row.check, defaults.*row.member), values(row.check), row.kind, row.hidden,
          std::string(row.config.key), std::string(row.config.want)};
}

template <class Table>
std::vector<RowInfo> infos(const Table& table) {
  std::vector<RowInfo> out;
  fields::for_each(table, [&](const auto& row) { out.push_back(info(row)); });
  return out;
}

// Applies `text` to the row's member; false: the check refused it.
template <class O, class T, class C>
bool apply(const Opt<O, T, C>& row, O& o, const std::string& text) {
  if (row.kind == Kind::off) {
    if constexpr (std::is_same_v<T, bool>) o.*row.member = false;
    return true;
  }
  if (row.kind == Kind::on && text.empty()) {
    if constexpr (std::is_same_v<T, bool>) o.*row.member = true;
    return true;
  }
  T v = o.*row.member;  // a parser may read the value so far (fts-server's --agones on)
  if (!parse(row.check, text, v)) return false;
  o.*row.member = std::move(v);
  return true;
}

// ---- the command line ---------------------------------------------------------------------

using EnvLookup = std::function<std::optional<std::string>(const std::string&)>;
inline EnvLookup no_env() {
  return [](const std::string&) { return std::nullopt; };
}

// What the command line said besides the rows' values.
struct Parsed {
  bool help = false;      // -h, --help
  bool markdown = false;  // --help-markdown: the reference
  std::set<std::string> given;     // the rows given (by flag or variable), flag without dashes
  std::vector<std::string> rest;   // arguments that are not flags (Program::positional)
};

struct Error {
  std::string message;
};

// A flag seen and its value ("" for a switch), or a variable read: what the rows apply.
struct Setting {
  std::size_t row;
  std::string text;
  std::string source;  // "--port" or "FTS_PORT"
};

// Splits the command line with CLI11 (--flag V, --flag=V, the last of a repeated flag
// wins) and reads the rows' variables; the settings come back in the order to apply
// them: every variable, then every flag. Errors: unknown flags, a missing value.
std::variant<std::vector<Setting>, Error> split(const Program& program, const std::vector<RowInfo>& rows,
                                                const std::vector<std::string>& args, const EnvLookup& env,
                                                Parsed& parsed);

// `source: want, got "text"` in the program's wording.
std::string refusal(const Program& program, const std::string& source, const std::string& want, const std::string& text);

// Parses args (without the program's name) into `o` (which holds the defaults, or what
// the caller already applied) by the table.
template <class O, class Table>
std::variant<Parsed, Error> parse(const Program& program, const Table& table, O& o, const std::vector<std::string>& args,
                                  const EnvLookup& env = no_env()) {
  const auto rows = infos(table);
  Parsed parsed;
  auto settings = split(program, rows, args, env, parsed);
  if (auto* e = std::get_if<Error>(&settings)) return *e;
  for (const Setting& s : std::get<std::vector<Setting>>(settings)) {
    std::size_t i = 0;
    bool ok = true;
    fields::for_each(table, [&](const auto& row) {
      if (i++ == s.row) ok = apply(row, o, s.text);
    });
    if (!ok) return Error{refusal(program, s.source, rows[s.row].want, s.text)};
    parsed.given.insert(rows[s.row].flag.substr(2));
  }
  return parsed;
}

// --help: the synopsis, one line per row (flag, help, [variable, default]), the about.
std::string help_text(const Program& program, const std::vector<RowInfo>& rows);
// --help-markdown: a section with a table (flag, variable when the program reads them,
// default, values, meaning).
std::string markdown(const Program& program, const std::vector<RowInfo>& rows, std::string_view title);

// The rows that a config file's key overrides, for the caller that reads the file:
// key_of(row) and a way to read the option's value as text or set it from a text.
template <class O, class Table, class Fn>
void for_each_config_row(const Table& table, O& o, Fn&& fn) {
  fields::for_each(table, [&](const auto& row) {
    if (row.config.key.empty()) return;
    const RowInfo ri = info(row);
    fn(ri, show(row.check, o.*row.member), [&](const std::string& text) { return apply(row, o, text); });
  });
}

}  // namespace fts::cli
