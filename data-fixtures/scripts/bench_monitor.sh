#!/usr/bin/env bash
# Time `ldh monitor` on simulated free-living pairs at 100 Hz (issue 52's performance targets,
# docs/benchmarks.md "Free-living monitoring"): a 1 h, a 24 h and, with --week, a 7-day pair.
# Each case: `ldh simulate --free-living` once (cached in $WORK), then
# `/usr/bin/time -v ldh monitor LEFT RIGHT -o OUT -j 1`, reporting wall time and peak RSS.
#
# Usage: data-fixtures/scripts/bench_monitor.sh [--week] [--ldh PATH] [--work DIR]
# Needs: an ldh binary with the `monitor` command (default target/ci/ldh, then target/release/ldh),
# GNU time at /usr/bin/time, about 3 GB of disk per simulated day (CSV).
set -euo pipefail

LDH=""
WORK="${TMPDIR:-/tmp}/ldh-bench-monitor"
CASES=(1 24)
while [ $# -gt 0 ]; do
  case "$1" in
    --week) CASES=(1 24 168) ;;
    --ldh) LDH="$2"; shift ;;
    --work) WORK="$2"; shift ;;
    -h|--help) sed -n 2,9p "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
  shift
done
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
if [ -z "$LDH" ]; then
  for c in "$ROOT/target/ci/ldh" "$ROOT/target/release/ldh"; do
    [ -x "$c" ] && { LDH="$c"; break; }
  done
fi
[ -n "$LDH" ] && [ -x "$LDH" ] || { echo "no ldh binary: build with cargo build --profile ci -p ldh-cli, or pass --ldh PATH" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "GNU time (/usr/bin/time) is needed for peak RSS: apt-get install time" >&2; exit 2; }
if ! "$LDH" monitor --help >/dev/null 2>&1; then
  echo "this ldh has no 'monitor' command yet (issue 52); nothing to time" >&2
  exit 3
fi
mkdir -p "$WORK"
printf '%-8s %12s %14s %14s\n' hours samples wall_s peak_rss_mb
for h in "${CASES[@]}"; do
  sim="$WORK/sim-${h}h"
  if [ ! -f "$sim/H01/truth.json" ]; then
    rm -rf "$sim"
    "$LDH" simulate --free-living --hours "$h" --seed 52 --rate-hz 100 -o "$sim" -j 1 >/dev/null
  fi
  out="$WORK/out-${h}h"
  rm -rf "$out"
  log="$WORK/time-${h}h.txt"
  if ! /usr/bin/time -v "$LDH" monitor "$sim/H01/left.csv" "$sim/H01/right.csv" -o "$out" -j 1 \
      >"$WORK/monitor-${h}h.log" 2>"$log"; then
    echo "ldh monitor failed on the ${h} h pair; see $log" >&2
    tail -n 30 "$log" >&2
    exit 1
  fi
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$log" \
    | awk -F: '{ if (NF == 3) print $1*3600 + $2*60 + $3; else print $1*60 + $2 }')
  rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$log")
  printf '%-8s %12s %14.1f %14.0f\n' "$h" "$((h * 360000))" "$wall" "$((rss_kb / 1024))"
done
