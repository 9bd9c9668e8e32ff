#!/usr/bin/env bash
# A throwaway PostgreSQL 15 (Debian's postgresql package) for tests, in DIR on PORT:
#   pg_temp.sh start DIR PORT    initdb on first use (superuser fts, trust), then start
#   pg_temp.sh stop DIR          fast shutdown (the data stays: start again later)
#   pg_temp.sh url DIR PORT      the URL fts-server takes (--profiles)
# initdb and pg_ctl refuse root: as root they run as the postgres user the package
# makes, and DIR is handed to it. Exit 77: no PostgreSQL 15 here (a test skips).
set -euo pipefail
bin=/usr/lib/postgresql/15/bin
cmd=${1:?usage: pg_temp.sh start|stop|url DIR [PORT]}
dir=${2:?usage: pg_temp.sh start|stop|url DIR [PORT]}
as=()
if [[ $(id -u) -eq 0 ]]; then as=(runuser -u postgres --); fi
case $cmd in
  start)
    port=${3:?start needs a PORT}
    [[ -x $bin/initdb ]] || { echo "pg_temp.sh: no $bin/initdb (apt-get install postgresql)" >&2; exit 77; }
    if [[ ${#as[@]} -gt 0 ]] && ! id postgres >/dev/null 2>&1; then echo "pg_temp.sh: no postgres user" >&2; exit 77; fi
    mkdir -p "$dir"
    # The postgres user must reach DIR: its parent (a test's mktemp -d, mode 700) is
    # opened for traversal (a+x, no listing).
    if [[ ${#as[@]} -gt 0 ]]; then chown postgres "$dir" && chmod a+x "$(dirname "$dir")"; fi
    if [[ ! -f $dir/data/PG_VERSION ]]; then
      "${as[@]}" "$bin/initdb" -D "$dir/data" -U fts --auth=trust -E UTF8 --no-sync >"$dir/initdb.log" 2>&1 ||
        { cat "$dir/initdb.log" >&2; exit 1; }
    fi
    # fsync stays on unless the caller turns it off (FTS_PG_FSYNC=off: tests that do not
    # measure); the socket lives in DIR, TCP only on loopback.
    "${as[@]}" "$bin/pg_ctl" -D "$dir/data" -l "$dir/pg.log" -w -t 30 \
      -o "-p $port -k $dir -c listen_addresses=127.0.0.1 -c fsync=${FTS_PG_FSYNC:-on}" start >/dev/null ||
      { cat "$dir/pg.log" >&2; exit 1; }
    ;;
  stop)
    [[ -f $dir/data/postmaster.pid ]] || exit 0
    "${as[@]}" "$bin/pg_ctl" -D "$dir/data" -m fast -w -t 30 stop >/dev/null
    ;;
  url)
    echo "postgresql://fts@127.0.0.1:${3:?url needs a PORT}/postgres?connect_timeout=2"
    ;;
  *) echo "pg_temp.sh: unknown command $cmd" >&2; exit 2 ;;
esac
