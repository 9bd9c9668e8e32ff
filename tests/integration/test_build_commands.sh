#!/usr/bin/env bash
# The Dockerfile, README and CI must build with the same scripts, so they cannot drift:
# docker/Dockerfile RUNs .ci/deps.sh and .ci/build.sh (and no cmake of its own), README's
# two commands are `bash .ci/play.sh` and `bash .ci/test.sh`, .ci/run runs `bash .ci/test.sh`,
# and those scripts in turn call .ci/deps.sh and .ci/build.sh. The README stays short and
# links every page of docs/.
#   test_build_commands.sh SOURCE_DIR
set -uo pipefail
root=${1:?usage: test_build_commands.sh SOURCE_DIR}
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then echo "ok   - $what"; else echo "FAIL - $what"; failures=$((failures + 1)); fi
}
has_line() { grep -Eq -- "$2" "$1"; }
lacks_line() { ! grep -Eq -- "$2" "$1"; }

dockerfile=$root/docker/Dockerfile
# RUN instructions, with backslash continuations joined.
runs=$(sed -e ':a' -e '/\\$/N; s/\\\n//; ta' "$dockerfile" | grep -E '^[[:space:]]*RUN[[:space:]]')
check "Dockerfile builds on debian:bookworm" has_line "$dockerfile" '^FROM debian:bookworm( |$)'
check "Dockerfile runs on debian:bookworm-slim" has_line "$dockerfile" '^FROM debian:bookworm-slim( |$)'
check "a Dockerfile RUN calls bash .ci/deps.sh" grep -Eq 'bash \.ci/deps\.sh' <<<"$runs"
check "a Dockerfile RUN calls bash .ci/build.sh" grep -Eq 'bash \.ci/build\.sh' <<<"$runs"
check "no Dockerfile RUN calls cmake or a compiler itself" bash -c '! grep -Eq "(^|[ ;&|])(cmake|ninja|make|g\+\+|c\+\+|clang\+\+)( |$)" <<<"$1"' _ "$runs"
build_dir=$(grep -Eo 'bash \.ci/build\.sh [^ ]+' <<<"$runs" | head -1 | awk '{print $3}')
check "the runtime stage copies fts-server from the build dir ($build_dir)" \
  has_line "$dockerfile" "^COPY --from=build .*${build_dir}/server/fts-server"
check "the runtime stage copies fts-bot from the build dir ($build_dir)" \
  has_line "$dockerfile" "^COPY --from=build .*${build_dir}/client/fts-bot"
check "Dockerfile runs as a non-root user" has_line "$dockerfile" '^USER [a-z]'
check "Dockerfile exposes 7777/udp" has_line "$dockerfile" '^EXPOSE 7777/udp'
check "Dockerfile health check uses fts-bot --probe" has_line "$dockerfile" 'fts-bot --probe'
check "Dockerfile entry point is fts-server --log-format json" \
  has_line "$dockerfile" '^ENTRYPOINT \["fts-server", "--log-format", "json"\]'
check "compose builds docker/Dockerfile" has_line "$root/docker/compose.yaml" 'dockerfile: docker/Dockerfile'
check "compose bots count comes from FTS_BOTS" has_line "$root/docker/compose.yaml" '"--count", "\$\{FTS_BOTS:-[0-9]+\}"'

readme=$root/README.md
check "README's main command is bash .ci/play.sh" has_line "$readme" '^    bash \.ci/play\.sh$'
check "README's test command is bash .ci/test.sh" has_line "$readme" '^    bash \.ci/test\.sh$'
# The README is the two-minute page: at most 150 lines, and it links every page of docs/.
check "README has at most 150 lines ($(wc -l <"$readme"))" test "$(wc -l <"$readme")" -le 150
for page in "$root"/docs/*.md; do
  check "README links docs/${page##*/}" grep -Fq "](docs/${page##*/})" "$readme"
done
check ".ci/run (CI) runs bash .ci/test.sh" has_line "$root/.ci/run" '^bash \.ci/test\.sh$'
for s in test play; do
  check ".ci/$s.sh installs with bash .ci/deps.sh" has_line "$root/.ci/$s.sh" '^bash \.ci/deps\.sh'
  check ".ci/$s.sh builds with bash .ci/build.sh" has_line "$root/.ci/$s.sh" '^bash \.ci/build\.sh '
  check ".ci/$s.sh does not run cmake itself" lacks_line "$root/.ci/$s.sh" '^[^#]*cmake '
done
check ".ci/build.sh is the one that runs cmake --build" has_line "$root/.ci/build.sh" '^cmake --build '

if ((failures)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all build-command checks passed"
