// fts-sim --match: a headless match with built-in bots, or the replay of an input log.
#pragma once

#include <string>
#include <vector>

namespace fts::simtool {

// args: the command line after "--match" was removed, e.g. {"--players", "4", "--seed", "7"}.
// Prints one JSON report to stdout; returns the process exit code (2: usage error).
int run_match_cli(const std::vector<std::string>& args);

// --help's and the reference's section for --match, from its option table.
std::string match_help();
std::string match_markdown();

}  // namespace fts::simtool
