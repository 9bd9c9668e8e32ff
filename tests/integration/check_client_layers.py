#!/usr/bin/env python3
"""Issue 27: the client does not depend on the server. Fails when a client target links
a server library (directly or through a library it links), when its include path reaches
server/, or when a file under client/ includes a header that exists only under server/.

usage: check_client_layers.py SOURCE_DIR LINKS_FILE
LINKS_FILE (written by CMake's file(GENERATE)) has one line per target:
    target|include dirs;...|linked libraries;..."""
import os, re, sys

CLIENT_TARGETS = {"fts-client", "fts-bot", "fts_client_ui", "fts_client_replay", "fts_bot_core"}
SERVER_LIBRARIES = {"fts_host", "fts_server_app", "fts_fleet", "fts-server", "fts-sim"}


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
    for target in sorted(CLIENT_TARGETS & deps.keys()):
        seen, todo = set(), list(deps[target])
        while todo:  # every library it links, through the libraries it links
            lib = re.sub(r"^\$<LINK_ONLY:(.*)>$", r"\1", todo.pop())
            if lib in seen:
                continue
            seen.add(lib)
            todo.extend(deps.get(lib, []))
        for lib in sorted(seen & SERVER_LIBRARIES):
            problems.append(f"{target} links the server library {lib}")
        for d in includes[target]:
            if os.path.realpath(d).startswith(server_dir):
                problems.append(f"{target} has server/ on its include path: {d}")
    # Headers included by client/ sources: none may be found only under server/.
    client_dir = os.path.join(source, "client")
    roots = [client_dir] + [os.path.join(source, p) for p in ("protocol/include", "protocol/io/include",
                                                                "protocol/room/include", "common/include")]
    for dirpath, _, files in os.walk(client_dir):
        for name in files:
            if not name.endswith((".cpp", ".hpp")):
                continue
            path = os.path.join(dirpath, name)
            with open(path, errors="replace") as f:
                for no, text in enumerate(f, 1):
                    m = re.match(r'\s*#\s*include\s+"([^"]+)"', text)
                    if not m:
                        continue
                    header = m.group(1)
                    here = os.path.exists(os.path.join(dirpath, header))
                    found = here or any(os.path.exists(os.path.join(r, header)) for r in roots)
                    if not found and os.path.exists(os.path.join(source, "server", header)):
                        problems.append(f"{os.path.relpath(path, source)}:{no} includes server/{header}")
    for p in problems:
        print("FAIL:", p)
    checked = sorted(CLIENT_TARGETS & deps.keys())
    print(f"checked {len(checked)} client targets ({', '.join(checked)}): {len(problems)} problems")
    return 1 if problems or len(checked) < 4 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
