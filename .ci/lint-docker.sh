#!/usr/bin/env bash
# Lints docker/Dockerfile without a Docker engine, with npm's dockerfile-utils (installed
# into .ci/node on first use; kept out of git). Needs the npm registry once, so CI, which
# has only Debian's mirror, does not run it; exits 77 (skip) when the linter cannot be
# installed (or, with FTS_LINT_NO_INSTALL=1 as CTest runs it, when it is not installed
# yet). Prints every finding and exits 1 if there is any.
#   bash .ci/lint-docker.sh [Dockerfile]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
file=${1:-$root/docker/Dockerfile}
prefix=$root/.ci/node
if [[ ! -d $prefix/node_modules/dockerfile-utils ]]; then
  if [[ ${FTS_LINT_NO_INSTALL:-0} == 1 ]]; then
    echo "lint-docker: dockerfile-utils not installed in .ci/node (run bash .ci/lint-docker.sh once); skipped" >&2
    exit 77
  fi
  if ! command -v npm >/dev/null || ! npm install --silent --no-audit --no-fund --prefix "$prefix" dockerfile-utils@0.16 >/dev/null 2>&1; then
    echo "lint-docker: cannot install dockerfile-utils from npm (offline?); skipped" >&2
    exit 77
  fi
fi
NODE_PATH=$prefix/node_modules node - "$file" <<'JS'
const fs = require("fs");
const { validate } = require("dockerfile-utils");
const file = process.argv[2];
const text = fs.readFileSync(file, "utf8");
const problems = validate(text, {});
for (const p of problems) {
  const where = `${file}:${p.range.start.line + 1}:${p.range.start.character + 1}`;
  console.log(`${where}: ${p.severity === 1 ? "error" : "warning"}: ${p.message}`);
}
console.log(`lint-docker: ${problems.length} finding(s) in ${file}`);
process.exit(problems.length ? 1 : 0);
JS
