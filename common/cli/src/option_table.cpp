#include "fts/cli/option_table.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <CLI/CLI.hpp>

namespace fts::cli {

std::string show_real(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

bool parse_real(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0') return false;
  out = v;
  return true;
}

bool parse(const OneOf& c, const std::string& text, std::string& out) {
  for (std::string_view n : c.names) {
    if (!n.empty() && n == text) {
      out = text;
      return true;
    }
  }
  return false;
}

std::string values(const OneOf& c) {
  std::string s;
  for (std::string_view n : c.names) {
    if (n.empty()) continue;
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

std::string refusal(const Program& program, const std::string& source, const std::string& want, const std::string& text) {
  const std::string q(program.wording.quote);
  return source + (program.wording.colon ? ": " : " ") + want + ", got " + q + text + q;
}

namespace {

std::string needs_value(const Program& program, const std::string& flag, const std::vector<RowInfo>& rows) {
  if (program.wording.colon) return flag + ": needs a value";
  for (const auto& r : rows)
    if (r.flag == flag && !r.value_name.empty()) return flag + " needs " + r.value_name;
  return flag + " needs a value";
}

}  // namespace

std::variant<std::vector<Setting>, Error> split(const Program& program, const std::vector<RowInfo>& rows,
                                                const std::vector<std::string>& args, const EnvLookup& env,
                                                Parsed& parsed) {
  CLI::App app{"", std::string(program.name)};
  app.set_help_flag();
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::vector<CLI::Option*> options;
  for (const auto& r : rows) options.push_back(r.kind == Kind::value ? app.add_option(r.flag) : app.add_flag(r.flag));
  const CLI::Option* help = app.add_flag("-h,--help");
  const CLI::Option* markdown = app.add_flag("--help-markdown");
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them reversed
  } catch (const CLI::ArgumentMismatch&) {
    // Only a value flag at the very end lacks its value (any next argument is taken).
    return Error{needs_value(program, args.back().substr(0, args.back().find('=')), rows)};
  } catch (const CLI::ParseError& e) {
    return Error{std::string(e.what()) + " (see --help)"};
  }
  parsed.help = help->count() > 0;
  parsed.markdown = markdown->count() > 0;
  for (const std::string& a : app.remaining()) {
    if (a.rfind("--", 0) == 0) return Error{"unknown flag " + a.substr(0, a.find('=')) + " (see --help)"};
    if (!program.positional) return Error{"unexpected argument \"" + a + "\" (see --help)"};
    parsed.rest.push_back(a);
  }
  std::vector<Setting> settings;
  if (program.reads_env) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].env.empty()) continue;
      if (auto v = env(rows[i].env)) settings.push_back({i, *v, rows[i].env});
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (options[i]->count() == 0) continue;
    settings.push_back({i, rows[i].kind == Kind::value ? options[i]->results().back() : "", rows[i].flag});
  }
  return settings;
}

namespace {

std::string flag_with_value(const RowInfo& r) { return r.value_name.empty() ? r.flag : r.flag + " " + r.value_name; }

// A default as the reader sees it: a switch's "off", an empty text's "(none)".
std::string shown_default(const RowInfo& r) {
  if (r.kind != Kind::value) return r.kind == Kind::on ? "off" : "on";
  return r.default_value;
}

// Markdown table cells: `|` would end the cell.
std::string cell(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else out += c;
  }
  return out;
}

}  // namespace

std::string help_text(const Program& program, const std::vector<RowInfo>& rows) {
  std::string s = std::string(program.synopsis) + "\nOptions";
  s += program.reads_env ? " (each also settable from the environment):\n" : ":\n";
  for (const auto& r : rows) {
    if (r.hidden) continue;
    std::string left = "  " + flag_with_value(r) + " ";
    if (left.size() < 30) left.resize(30, ' ');
    std::string note;
    if (program.reads_env && !r.env.empty()) note = r.env + (r.kind == Kind::on ? "=1" : "");
    const std::string d = shown_default(r);
    if (!d.empty() && r.kind == Kind::value) note += (note.empty() ? "" : ", ") + std::string("default ") + d;
    s += left + r.help + (note.empty() ? "" : " [" + note + "]") + "\n";
  }
  s += "  -h, --help                  this text\n";
  if (!program.about.empty()) s += "\n" + std::string(program.about);
  return s;
}

std::string markdown(const Program& program, const std::vector<RowInfo>& rows, std::string_view title) {
  std::string s = "## " + std::string(title) + "\n\n```\n" + std::string(program.synopsis) + "```\n\n";
  s += program.reads_env ? "| flag | environment | default | values | meaning |\n|---|---|---|---|---|\n"
                         : "| flag | default | values | meaning |\n|---|---|---|---|\n";
  for (const auto& r : rows) {
    if (r.hidden) continue;
    s += "| `" + cell(flag_with_value(r)) + "` | ";
    if (program.reads_env) s += r.env.empty() ? "| " : "`" + r.env + (r.kind == Kind::on ? "=1" : "") + "` | ";
    const std::string d = shown_default(r);
    const std::string shown = r.kind != Kind::value ? d : d.empty() ? "(none)" : "`" + cell(d) + "`";
    s += shown + " | " + cell(r.values) + " | " + cell(r.help) + " |\n";
  }
  s += "| `-h`, `--help` | ";
  if (program.reads_env) s += "| ";
  s += "| | this text |\n";
  if (!program.about.empty()) s += "\n```\n" + std::string(program.about) + "```\n";
  return s;
}

}  // namespace fts::cli
