#!/usr/bin/env python3
"""The flag references docs/flags/<program>.md are each program's `--help-markdown`, which
comes from its option table (issue 38); this test fails when a committed page differs from
what the built program prints, or when a flag of `--help` is missing from its page (and
the other way round).

usage: flags_docs.py BIN_DIR SOURCE_DIR            check (ctest flags_docs, label hosting)
       flags_docs.py BIN_DIR SOURCE_DIR --write    regenerate the pages
BIN_DIR is a build directory (server/fts-server, server/fts-sim, client/fts-client, client/fts-bot)."""
import difflib
import os
import re
import subprocess
import sys

PROGRAMS = {"fts-server": "server", "fts-sim": "server", "fts-client": "client", "fts-bot": "client"}
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")


def run(binary, flag):
    p = subprocess.run([binary, flag], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        sys.exit(f"FAIL - {binary} {flag}: exit {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    bin_dir, src = sys.argv[1], sys.argv[2]
    write = "--write" in sys.argv[3:]
    failures = []
    for prog, sub in PROGRAMS.items():
        binary = os.path.join(bin_dir, sub, prog)
        page = os.path.join(src, "docs", "flags", prog + ".md")
        markdown = run(binary, "--help-markdown")
        if write:
            with open(page, "w") as f:
                f.write(markdown)
            print(f"wrote {page}")
            continue
        committed = open(page).read() if os.path.exists(page) else ""
        if committed != markdown:
            diff = "".join(difflib.unified_diff(committed.splitlines(True), markdown.splitlines(True),
                                                f"docs/flags/{prog}.md (committed)", f"{prog} --help-markdown"))
            failures.append(f"docs/flags/{prog}.md differs from `{prog} --help-markdown` "
                            f"(regenerate: python3 tests/integration/flags_docs.py BUILD_DIR . --write):\n{diff}")
        helped = set(FLAG.findall(run(binary, "--help")))
        documented = set(FLAG.findall(committed))
        # Every flag row of the reference's tables is in --help too.
        rows = set(m.group(1) for m in re.finditer(r"^\| `(--[a-z0-9-]+)", committed, re.M))
        for flag in sorted(helped - documented):
            failures.append(f"{prog} --help names {flag}, docs/flags/{prog}.md does not")
        for flag in sorted(rows - helped):
            failures.append(f"docs/flags/{prog}.md has a row for {flag}, {prog} --help does not")
        if not rows:
            failures.append(f"docs/flags/{prog}.md has no flag rows")
    for f in failures:
        print("FAIL -", f)
    if failures:
        sys.exit(1)
    if not write:
        print(f"ok: {len(PROGRAMS)} flag references equal their programs' --help-markdown")


if __name__ == "__main__":
    main()
