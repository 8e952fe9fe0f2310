#!/usr/bin/env bash
# A throwaway PostgreSQL cluster for the tests: Debian's postgresql binaries, a
# temporary directory, a free port on 127.0.0.1, one user (floe) trusted without a
# password, fsync off (the tests kill Floe, never PostgreSQL).
#
#   pg=$(bash scripts/pg-test-cluster.sh start) && eval "$pg"   # sets FLOE_TEST_DATABASE_URL, FLOE_TEST_PG_DIR
#   bash scripts/pg-test-cluster.sh stop "$FLOE_TEST_PG_DIR"
#
# PostgreSQL refuses to run as root: as root, the cluster runs as the postgres user
# the Debian package creates.
set -euo pipefail
bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)
if [ -z "$bin" ]; then
  echo "no PostgreSQL server binaries in /usr/lib/postgresql (Debian: apt-get install postgresql)" >&2
  exit 1
fi
as_owner() {
  if [ "$(id -u)" = 0 ]; then runuser -u postgres -- "$@"; else "$@"; fi
}
case "${1:-start}" in
  start)
    dir=$(mktemp -d /tmp/floe-pg.XXXXXX)
    [ "$(id -u)" = 0 ] && chown postgres: "$dir"
    as_owner "$bin/initdb" -D "$dir/data" -U floe -A trust -E UTF8 --no-sync >"$dir/initdb.log" 2>&1 ||
      { cat "$dir/initdb.log" >&2; exit 1; }
    # A port below the kernel's ephemeral range (32768 up), where no outgoing
    # connection takes one, that nothing listens on; another try on another port if
    # it was taken all the same before PostgreSQL bound it.
    for attempt in 1 2 3 4 5; do
      while :; do
        port=$((20000 + RANDOM % 12000))
        (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || break
      done
      if as_owner "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w \
        -o "-p $port -k $dir -c listen_addresses=127.0.0.1 -c fsync=off -c max_connections=200" start >/dev/null; then
        echo "export FLOE_TEST_DATABASE_URL=postgres://floe@127.0.0.1:$port/postgres FLOE_TEST_PG_DIR=$dir"
        exit 0
      fi
      echo "PostgreSQL did not start on port $port (try $attempt of 5)" >&2
    done
    cat "$dir/server.log" >&2
    exit 1
    ;;
  stop)
    dir=${2:?usage: pg-test-cluster.sh stop DIR}
    as_owner "$bin/pg_ctl" -D "$dir/data" -m fast -w stop >/dev/null || true
    rm -rf "$dir"
    ;;
  *)
    echo "usage: pg-test-cluster.sh start | stop DIR" >&2
    exit 2
    ;;
esac
