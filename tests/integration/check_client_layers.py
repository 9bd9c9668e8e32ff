#!/usr/bin/env python3
"""The module boundaries (issue 27, issue 38 part 4). Fails when a client target links
a server library (directly or through a library it links), when its include path reaches
server/, or when a file under client/ includes a header that exists only under server/;
and when a lower module reaches a higher one: LINK_RULES (what a target may never link,
through any library) and SOURCE_RULES (which headers the files under a path may never
include).

usage: check_client_layers.py SOURCE_DIR LINKS_FILE
LINKS_FILE (written by CMake's file(GENERATE)) has one line per target:
    target|include dirs;...|linked libraries;..."""
import os, re, sys

CLIENT_LIBRARIES = {"fts_client_predict", "fts_client_net", "fts_client_term", "fts_client_ui",
                    "fts_client_replay", "fts_bot_core"}
CLIENT_TARGETS = CLIENT_LIBRARIES | {"fts-client", "fts-bot"}
SERVER_LIBRARIES = {"fts_store", "fts_server_app", "fts_fleet", "fts-server", "fts-sim"}
# The client's folders, as its files include them ("net/net_timing.hpp").
CLIENT_FOLDERS = ("predict/", "net/", "term/", "ui/", "bot/", "replay/")
# (targets, libraries they may never link through any library, why). The layers from the
# bottom: common (the match), protocol (the wire, sans-I/O) and fts_io (the socket), room
# (the stepper, the history), then server and client beside each other. Inside the client:
# predict < net < ui, term < ui but apart from predict and net, replay above ui; none of
# them opens a socket; fts-bot draws nothing.
ABOVE = "a layer above it"
LINK_RULES = [
    ({"fts_common"}, {"fts_protocol", "fts_io", "fts_room"} | SERVER_LIBRARIES | CLIENT_LIBRARIES, ABOVE),
    ({"fts_protocol", "fts_io"}, {"fts_room"} | SERVER_LIBRARIES | CLIENT_LIBRARIES, ABOVE),
    ({"fts_room"}, {"fts_io"} | SERVER_LIBRARIES | CLIENT_LIBRARIES, ABOVE),
    ({"fts_client_predict"}, CLIENT_LIBRARIES - {"fts_client_predict"} | {"fts_io", "fts_room"},
     "which predict/ may not use (predict < net < ui; term apart; no socket)"),
    ({"fts_client_net"}, CLIENT_LIBRARIES - {"fts_client_predict", "fts_client_net"} | {"fts_io", "fts_room"},
     "which net/ may not use (predict < net < ui; term apart; no socket)"),
    ({"fts_client_term"}, CLIENT_LIBRARIES - {"fts_client_term"} | {"fts_io", "fts_room"},
     "which term/ may not use (it stands apart from predict/, net/ and ui/)"),
    ({"fts_client_ui"}, {"fts_client_replay", "fts_bot_core", "fts_io", "fts_room"}, ABOVE),
    ({"fts_bot_core"}, {"fts_client_ui", "fts_client_term", "fts_client_replay", "fts_io", "fts_room"},
     "which fts_bot_core may not use (a bot draws nothing; fts-bot adds the socket)"),
    ({"fts-bot"}, {"fts_client_ui", "fts_client_term", "fts_client_replay", "fts_room"},
     "which fts-bot may not use (a bot draws nothing)"),
]
# (path prefix under the source, header prefixes its files may never include, why):
# protocol/ is the wire and knows no room; room/ reads and writes histories but opens no
# socket and knows no client; in client/, the folders follow LINK_RULES (term/'s library
# part only: terminal.cpp and io.cpp paint ui/'s screens and belong to fts-client).
SOURCE_RULES = [
    ("common/", ("fts/protocol/", "fts/io/", "fts/room/", "store/", "app/") + CLIENT_FOLDERS,
     "a layer above common/"),
    ("protocol/", ("fts/room/", "store/", "app/") + CLIENT_FOLDERS, "a layer above protocol/"),
    ("room/", ("fts/io/", "store/", "app/") + CLIENT_FOLDERS, "a layer above room/"),
    ("client/predict/", ("fts/io/", "net/", "term/", "ui/", "bot/", "replay/"),
     "a layer above client/predict/"),
    ("client/net/", ("fts/io/", "term/", "ui/", "bot/", "replay/"), "a layer above client/net/"),
    ("client/term/keys.", ("predict/", "net/", "ui/", "bot/", "replay/"),
     "which term/'s library stands apart from"),
    ("client/term/hangup.", ("predict/", "net/", "ui/", "bot/", "replay/"),
     "which term/'s library stands apart from"),
    ("client/ui/", ("fts/io/", "bot/", "replay/"), "a layer above client/ui/"),
    ("client/bot/", ("fts/io/", "term/", "ui/", "replay/"), "which fts-bot may not use (a bot draws nothing)"),
]


def quoted_includes(top):
    """(file, line number, header) of every #include "..." in the C++ files under top."""
    for dirpath, _, files in os.walk(top):
        for name in sorted(files):
            if not name.endswith((".cpp", ".hpp")):
                continue
            path = os.path.join(dirpath, name)
            with open(path, errors="replace") as f:
                for no, text in enumerate(f, 1):
                    m = re.match(r'\s*#\s*include\s+"([^"]+)"', text)
                    if m:
                        yield path, no, m.group(1)


def main(source, links_file):
    server_dir = os.path.realpath(os.path.join(source, "server"))
    deps, includes = {}, {}
    with open(links_file) as f:
        for line in f:
            if not line.strip():
                continue
            target, inc, libs = line.rstrip("\n").split("|")
            includes[target] = [i for i in inc.split(";") if i]
            deps[target] = [l for l in libs.split(";") if l]
    problems = []

    def linked(target):  # every library it links, through the libraries it links
        seen, todo = set(), list(deps[target])
        while todo:
            lib = re.sub(r"^\$<LINK_ONLY:(.*)>$", r"\1", todo.pop())
            if lib in seen:
                continue
            seen.add(lib)
            todo.extend(deps.get(lib, []))
        return seen

    for targets, forbidden, why in LINK_RULES:
        for target in sorted(targets & deps.keys()):
            for lib in sorted(linked(target) & forbidden):
                problems.append(f"{target} links {lib}, {why}")
    for target in sorted(CLIENT_TARGETS & deps.keys()):
        for lib in sorted(linked(target) & SERVER_LIBRARIES):
            problems.append(f"{target} links the server library {lib}")
        for d in includes[target]:
            if os.path.realpath(d).startswith(server_dir):
                problems.append(f"{target} has server/ on its include path: {d}")
    # Headers included by client/ sources: none may be found only under server/.
    client_dir = os.path.join(source, "client")
    roots = [client_dir] + [os.path.join(source, p) for p in ("protocol/include", "protocol/io/include",
                                                                "room/include", "common/include")]
    for path, no, header in quoted_includes(client_dir):
        here = os.path.exists(os.path.join(os.path.dirname(path), header))
        found = here or any(os.path.exists(os.path.join(r, header)) for r in roots)
        if not found and os.path.exists(os.path.join(source, "server", header)):
            problems.append(f"{os.path.relpath(path, source)}:{no} includes server/{header}")
    for where, prefixes, why in SOURCE_RULES:
        top = os.path.join(source, where.split("/")[0])
        for path, no, header in quoted_includes(top):
            rel = os.path.relpath(path, source)
            if rel.startswith(where) and header.startswith(prefixes):
                problems.append(f"{rel}:{no} includes {header}, {why}")
    for p in problems:
        print("FAIL:", p)
    checked = sorted(CLIENT_TARGETS & deps.keys())
    layered = sorted(set().union(*(t for t, _, _ in LINK_RULES)) & deps.keys())
    print(f"checked {len(checked)} client targets ({', '.join(checked)}), {len(layered)} layered targets "
          f"({', '.join(layered)}), {len(SOURCE_RULES)} folders' includes: {len(problems)} problems")
    # Fewer targets than the rules name: a target was renamed and its rules check nothing.
    return 1 if problems or len(checked) < len(CLIENT_TARGETS) or len(layered) < 10 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
