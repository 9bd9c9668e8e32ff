#!/usr/bin/env bash
# Lints docker/Dockerfile without a Docker engine, with npm's dockerfile-utils (the
# parser/validator of the VS Code Docker extension) and dockerfilelint, installed into
# .ci/node on first use (kept out of git). Needs the npm registry once, so CI, which has
# only Debian's mirror, does not depend on it: exits 77 (skip) when the linters cannot be
# installed (or, with FTS_LINT_NO_INSTALL=1 as CTest runs it, are not installed yet).
# Prints every finding and exits 1 if there is any.
#   bash .ci/lint-docker.sh [Dockerfile]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
file=${1:-$root/docker/Dockerfile}
prefix=$root/.ci/node
if [[ ! -d $prefix/node_modules/dockerfile-utils || ! -d $prefix/node_modules/dockerfilelint ]]; then
  if [[ ${FTS_LINT_NO_INSTALL:-0} == 1 ]]; then
    echo "lint-docker: linters not installed in .ci/node (run bash .ci/lint-docker.sh once); skipped" >&2
    exit 77
  fi
  if ! command -v npm >/dev/null ||
     ! npm install --silent --no-audit --no-fund --prefix "$prefix" dockerfile-utils@0.16 dockerfilelint@1.8 >/dev/null 2>&1; then
    echo "lint-docker: cannot install the linters from npm (offline?); skipped" >&2
    exit 77
  fi
fi
status=0
NODE_PATH=$prefix/node_modules node - "$file" <<'JS' || status=1
const fs = require("fs");
const { validate } = require("dockerfile-utils");
const file = process.argv[2];
const problems = validate(fs.readFileSync(file, "utf8"), {});
for (const p of problems) {
  const where = `${file}:${p.range.start.line + 1}:${p.range.start.character + 1}`;
  console.log(`${where}: ${p.severity === 1 ? "error" : "warning"}: ${p.message}`);
}
console.log(`lint-docker: dockerfile-utils: ${problems.length} finding(s) in ${file}`);
process.exit(problems.length ? 1 : 0);
JS
if out=$("$prefix/node_modules/.bin/dockerfilelint" "$file"); then
  echo "lint-docker: dockerfilelint: 0 finding(s) in $file"
else
  echo "$out"
  echo "lint-docker: dockerfilelint: findings in $file"
  status=1
fi
exit $status
