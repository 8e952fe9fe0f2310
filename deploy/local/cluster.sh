#!/usr/bin/env bash
# A Floe cluster on loopback, for a laptop or a test: a throwaway PostgreSQL, N
# workers (`floe serve --worker floe-K`) sharing it and one checkpoint directory,
# and nginx in front routing as the Kubernetes proxy does (nginx.conf.template).
#
#   eval "$(deploy/local/cluster.sh start DIR 3)"   # FLOE_PROXY_GRPC, FLOE_PROXY_HTTP, ...
#   deploy/local/cluster.sh stop DIR
#
# Everything lives in DIR (created if missing; the caller removes it): pg/ (the
# database, its socket and log), shared/ (the workers' --data-dir), worker-K.log and
# worker-K.pid, nginx/ (config, pid, logs). Starting again on a DIR that was stopped
# keeps its database and checkpoints, as a restart of the whole cluster would. start
# prints only `export` lines on stdout, so that `eval` works; progress and errors go
# to stderr. A start that fails stops whatever it had started.
#
# Environment:
#   FLOE_BIN            the floe binary (default: target/release/floe of this checkout)
#   FLOE_LEASE          the workers' --lease in seconds (default 10)
#   FLOE_NGINX          the nginx binary (default: nginx on PATH, else /usr/sbin/nginx)
#   FLOE_CLUSTER_WAIT   seconds start waits for each part to answer (default 120)
#   FLOE_STOP_WAIT      seconds stop waits for each worker after SIGTERM (default 120:
#                       a worker checkpoints every scene before it exits)
# Other settings reach the workers through the FLOE_* variables `floe serve` reads
# (FLOE_BACKEND, FLOE_CHECKPOINT_EVERY, FLOE_MAX_SCENES, ...), which they inherit.
#
# PostgreSQL refuses to run as root: as root, it runs as the postgres user the
# Debian package creates (as scripts/pg-test-cluster.sh does). Debian packages:
# postgresql, nginx, python3 (free ports and readiness checks).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

usage() {
  echo "usage: cluster.sh start DIR N | stop DIR" >&2
  exit 2
}

say() { echo "cluster.sh: $*" >&2; }
die() {
  say "$*"
  exit 1
}

as_postgres() {
  if [ "$(id -u)" = 0 ]; then runuser -u postgres -- "$@"; else "$@"; fi
}

pg_bin() {
  local bin
  bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)
  [ -n "$bin" ] || die "no PostgreSQL server binaries in /usr/lib/postgresql (Debian: apt-get install postgresql)"
  echo "$bin"
}

# COUNT distinct free ports on 127.0.0.1, below the kernel's ephemeral range (32768
# up on Linux), where no outgoing connection can take one between their choice and
# the components' binding them (a port the OS hands out for port 0 is in that range).
# Every socket stays bound until all are chosen, so no port comes out twice.
free_ports() {
  python3 - "$1" <<'PY'
import random, socket, sys
socks = []
while len(socks) < int(sys.argv[1]):
    s = socket.socket()
    try:
        s.bind(("127.0.0.1", random.randrange(20000, 32000)))
    except OSError:
        s.close()
        continue
    socks.append(s)
print(" ".join(str(s.getsockname()[1]) for s in socks))
PY
}

# Whether URL answers HTTP with any status: a worker binds its ports before it
# opens the database and joins the cluster, so a bare TCP connect would succeed on
# a worker that does not serve yet.
http_answers() {
  python3 - "$1" <<'PY'
import sys, urllib.error, urllib.request
try:
    urllib.request.urlopen(sys.argv[1], timeout=2).close()
except urllib.error.HTTPError:
    pass
except Exception:
    sys.exit(1)
PY
}

tcp_accepts() {
  (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null
}

# Whether PID runs and is not a zombie (a container whose init does not reap
# leaves exited workers as zombies, which kill -0 still finds).
alive() {
  local state
  kill -0 "$1" 2>/dev/null || return 1
  state=$(sed -n 's/^.*) \(.\).*/\1/p' "/proc/$1/stat" 2>/dev/null) || return 1
  [ "$state" != Z ]
}

# The pid in FILE when that process is still the one this cluster started (its
# command line names MARK, a path inside DIR), so a stale pid file never makes us
# signal an unrelated process that reused the number.
our_pid() {
  local file=$1 mark=$2 pid
  [ -f "$file" ] || return 1
  pid=$(cat "$file")
  [[ "$pid" =~ ^[0-9]+$ ]] || return 1
  alive "$pid" || return 1
  tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null | grep -qF -- "$mark" || return 1
  echo "$pid"
}

# Waits up to SECONDS for PID to exit.
wait_exit() {
  local pid=$1 seconds=$2 i
  for ((i = 0; i < seconds * 10; i++)); do
    alive "$pid" || return 0
    sleep 0.1
  done
  return 1
}

stop_cluster() {
  local dir=$1 pid f pids=()
  # nginx first, so no call reaches a worker that is going away. TERM is nginx's
  # fast shutdown: QUIT would wait for streams that last hours.
  if pid=$(our_pid "$dir/nginx/nginx.pid" "$dir/nginx"); then
    kill -TERM "$pid" 2>/dev/null || true
    wait_exit "$pid" 10 || { say "nginx ($pid) did not stop; killing it"; kill -KILL "$pid" 2>/dev/null || true; }
  fi
  rm -f "$dir/nginx/nginx.pid"
  # Every worker at once: each checkpoints its scenes on SIGTERM, in parallel.
  for f in "$dir"/worker-*.pid; do
    [ -e "$f" ] || continue
    if pid=$(our_pid "$f" "$dir/shared"); then
      kill -TERM "$pid" 2>/dev/null || true
      pids+=("$pid")
    fi
  done
  for pid in "${pids[@]}"; do
    wait_exit "$pid" "${FLOE_STOP_WAIT:-120}" ||
      { say "worker $pid did not exit within ${FLOE_STOP_WAIT:-120} s of SIGTERM; killing it"; kill -KILL "$pid" 2>/dev/null || true; }
  done
  rm -f "$dir"/worker-*.pid
  if [ -f "$dir/pg/data/postmaster.pid" ]; then
    as_postgres "$(pg_bin)/pg_ctl" -D "$dir/pg/data" -m fast -w stop >/dev/null || true
  fi
}

start_cluster() {
  local dir=$1 n=$2
  [[ "$n" =~ ^[1-9][0-9]*$ ]] || die "N must be a positive number of workers, not '$n'"
  local bin=${FLOE_BIN:-$root/target/release/floe}
  [ -x "$bin" ] || die "no floe binary at $bin (cargo build --release, or set FLOE_BIN)"
  local nginx=${FLOE_NGINX:-$(command -v nginx || echo /usr/sbin/nginx)}
  [ -x "$nginx" ] || die "no nginx (Debian: apt-get install nginx, or set FLOE_NGINX)"
  command -v python3 >/dev/null || die "python3 is needed (free ports, readiness checks)"
  local pgbin
  pgbin=$(pg_bin)
  local wait_s=${FLOE_CLUSTER_WAIT:-120}

  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  if our_pid "$dir/nginx/nginx.pid" "$dir/nginx" >/dev/null ||
    { [ -d "$dir/pg/data" ] && as_postgres "$pgbin/pg_ctl" -D "$dir/pg/data" status >/dev/null 2>&1; }; then
    die "a cluster already runs in $dir (cluster.sh stop $dir first)"
  fi
  # From here on, leaving early (an error, die, Ctrl-C) stops whatever was started.
  # The trap runs after this function returns: it reads globals.
  starting_dir=$dir
  trap 'if [ -n "${starting_dir:-}" ]; then say "start failed; stopping what was started"; stop_cluster "$starting_dir"; fi' EXIT

  local ports_text ports
  ports_text=$(free_ports $((2 * n + 3)))
  read -r -a ports <<<"$ports_text"
  local pg_port=${ports[0]} proxy_http=${ports[1]} proxy_grpc=${ports[2]}

  # PostgreSQL: trusted local user floe, socket in DIR/pg, fsync off (a stop shuts it
  # down cleanly; only a crash of the machine could lose data, and this is a
  # throwaway).
  mkdir -p "$dir/pg"
  if [ "$(id -u)" = 0 ]; then
    chown postgres: "$dir/pg"
    # postgres must be able to pass through DIR to reach DIR/pg; traversal only, not listing.
    chmod o+x "$dir"
    runuser -u postgres -- test -w "$dir/pg" || die "the postgres user cannot write $dir/pg (a parent directory closed to others?)"
  fi
  if [ ! -f "$dir/pg/data/PG_VERSION" ]; then
    as_postgres "$pgbin/initdb" -D "$dir/pg/data" -U floe -A trust -E UTF8 --no-sync >"$dir/pg-initdb.log" 2>&1 ||
      { cat "$dir/pg-initdb.log" >&2; die "initdb failed"; }
  fi
  as_postgres "$pgbin/pg_ctl" -D "$dir/pg/data" -l "$dir/pg/server.log" -w \
    -o "-p $pg_port -k $dir/pg -c listen_addresses=127.0.0.1 -c fsync=off -c max_connections=200" start >/dev/null ||
    { tail -n 20 "$dir/pg/server.log" >&2; die "PostgreSQL did not start"; }
  local database=postgres://floe@127.0.0.1:$pg_port/postgres
  say "PostgreSQL on 127.0.0.1:$pg_port"

  # The workers, all started before any is waited for: they join the cluster
  # concurrently, as they would after a restart.
  mkdir -p "$dir/shared"
  local k grpc_port http_port
  for ((k = 1; k <= n; k++)); do
    grpc_port=${ports[2 * k + 1]}
    http_port=${ports[2 * k + 2]}
    # Standard streams go to the log: a process left holding the caller's stdout
    # would keep `eval "$(cluster.sh start ...)"` waiting for ever.
    "$bin" serve --worker "floe-$k" --database "$database" --data-dir "$dir/shared" \
      --grpc "127.0.0.1:$grpc_port" --http "127.0.0.1:$http_port" \
      --advertise-grpc "127.0.0.1:$grpc_port" --advertise-http "127.0.0.1:$http_port" \
      --scene none --auth off --lease "${FLOE_LEASE:-10}" \
      </dev/null >"$dir/worker-$k.log" 2>&1 &
    echo $! >"$dir/worker-$k.pid"
  done

  # The proxy's configuration: the template with its two listen addresses filled
  # in, and the workers' addresses beside it.
  mkdir -p "$dir/nginx/tmp"
  sed -e "s|\${FLOE_PROXY_HTTP}|127.0.0.1:$proxy_http|g" -e "s|\${FLOE_PROXY_GRPC}|127.0.0.1:$proxy_grpc|g" \
    "$here/nginx.conf.template" >"$dir/nginx/nginx.conf"
  # shellcheck disable=SC2016 # the literal text ${FLOE_, a placeholder left unfilled
  ! grep -q '\${FLOE_' "$dir/nginx/nginx.conf" || die "nginx.conf.template has a placeholder cluster.sh does not fill"
  {
    echo "# Written by cluster.sh for this cluster's workers."
    echo "upstream floe_grpc_any {"
    for ((k = 1; k <= n; k++)); do echo "    server 127.0.0.1:${ports[2 * k + 1]};"; done
    echo "}"
    echo "upstream floe_http_any {"
    for ((k = 1; k <= n; k++)); do echo "    server 127.0.0.1:${ports[2 * k + 2]};"; done
    echo "}"
    echo "map \$floe_grpc_name \$floe_grpc_upstream {"
    echo "    default floe_grpc_any;"
    for ((k = 1; k <= n; k++)); do echo "    floe-$k 127.0.0.1:${ports[2 * k + 1]};"; done
    echo "}"
    echo "map \$floe_http_name \$floe_http_upstream {"
    echo "    default floe_http_any;"
    for ((k = 1; k <= n; k++)); do echo "    floe-$k 127.0.0.1:${ports[2 * k + 2]};"; done
    echo "}"
  } >"$dir/nginx/workers.conf"
  local out
  out=$("$nginx" -t -q -p "$dir/nginx" -c "$dir/nginx/nginx.conf" 2>&1) ||
    { echo "$out" >&2; die "nginx rejected $dir/nginx/nginx.conf"; }

  local i pid
  for ((k = 1; k <= n; k++)); do
    pid=$(cat "$dir/worker-$k.pid")
    for ((i = 0; ; i++)); do
      alive "$pid" || { tail -n 20 "$dir/worker-$k.log" >&2; die "worker floe-$k exited (log: $dir/worker-$k.log)"; }
      http_answers "http://127.0.0.1:${ports[2 * k + 2]}/metrics" && tcp_accepts "${ports[2 * k + 1]}" && break
      [ "$i" -lt $((wait_s * 5)) ] || { tail -n 20 "$dir/worker-$k.log" >&2; die "worker floe-$k did not answer within $wait_s s"; }
      sleep 0.2
    done
    say "worker floe-$k (pid $pid): gRPC 127.0.0.1:${ports[2 * k + 1]}, HTTP 127.0.0.1:${ports[2 * k + 2]}"
  done

  "$nginx" -p "$dir/nginx" -c "$dir/nginx/nginx.conf" </dev/null >"$dir/nginx/stdout.log" 2>&1 &
  # nginx writes the same pid into nginx.pid once it runs; written here too so a
  # failed start can stop it.
  pid=$!
  echo "$pid" >"$dir/nginx/nginx.pid"
  for ((i = 0; ; i++)); do
    alive "$pid" || { cat "$dir/nginx/stdout.log" "$dir/nginx/error.log" 2>/dev/null >&2; die "nginx exited"; }
    http_answers "http://127.0.0.1:$proxy_http/healthz" && tcp_accepts "$proxy_grpc" && break
    [ "$i" -lt $((wait_s * 5)) ] || die "nginx did not answer within $wait_s s"
    sleep 0.2
  done
  say "proxy: gRPC 127.0.0.1:$proxy_grpc, HTTP 127.0.0.1:$proxy_http"
  starting_dir=

  printf 'export %s=%q\n' \
    FLOE_PROXY_GRPC "http://127.0.0.1:$proxy_grpc" \
    FLOE_PROXY_HTTP "http://127.0.0.1:$proxy_http" \
    FLOE_CLUSTER_DIR "$dir" \
    FLOE_CLUSTER_DATABASE_URL "$database" \
    FLOE_CLUSTER_WORKERS "$n"
  for ((k = 1; k <= n; k++)); do
    printf 'export %s=%q\n' \
      "FLOE_CLUSTER_WORKER_${k}_PID" "$(cat "$dir/worker-$k.pid")" \
      "FLOE_CLUSTER_WORKER_${k}_GRPC" "http://127.0.0.1:${ports[2 * k + 1]}" \
      "FLOE_CLUSTER_WORKER_${k}_HTTP" "http://127.0.0.1:${ports[2 * k + 2]}"
  done
}

case "${1:-}" in
  start)
    [ $# = 3 ] || usage
    start_cluster "$2" "$3"
    ;;
  stop)
    [ $# = 2 ] || usage
    [ -d "$2" ] || die "no cluster directory $2"
    stop_cluster "$(cd "$2" && pwd)"
    ;;
  *)
    usage
    ;;
esac
