#!/usr/bin/env bash
# Time `ldh monitor` on simulated free-living pairs at 100 Hz (issue 52's performance targets,
# docs/benchmarks.md "Free-living monitoring"): a 1 h, a 24 h and, with --week, a 7-day pair.
# Each case: `ldh simulate --free-living` once (cached in $WORK), then
# `/usr/bin/time -v ldh monitor LEFT RIGHT -o OUT -j 1` REPEAT times (default 3), reporting the
# medians of wall time, CPU time (user + system: less sensitive to a shared machine's load),
# peak RSS and the 1-minute load average as each run started (each run's figures on stderr).
#
# With --week-from-day the 7-day pair is the 24 h pair seven times over, each leg's clock
# continuing where the day before ended (the right sensor's drift goes on): the same per-sample
# cost without simulating a week (about an hour on a loaded 2-core machine).
# With --day-from-hour the 24 h pair is the 1 h pair 24 times over (in $WORK/day-from-hour):
# the same content per hour, so `24 h / 1 h` tests that cost is linear in length (a simulated
# day has a night, non-wear and cycling, and a third of the hour's walking per hour).
#
# Usage: data-fixtures/scripts/bench_monitor.sh [--week | --week-from-day] [--day-from-hour]
#        [--hours "1 24"] [--repeat N] [--ldh PATH] [--work DIR]
# Needs: an ldh binary with the `monitor` command (default target/ci/ldh, then target/release/ldh),
# GNU time at /usr/bin/time, about 3 GB of disk per simulated day (CSV).
set -euo pipefail

LDH=""
WORK="${TMPDIR:-/tmp}/ldh-bench-monitor"
CASES=(1 24)
REPEAT=3
FROM_DAY=0
FROM_HOUR=0
while [ $# -gt 0 ]; do
  case "$1" in
    --week) CASES=(1 24 168) ;;
    --week-from-day) CASES=(1 24 168); FROM_DAY=1 ;;
    --day-from-hour) FROM_HOUR=1 ;;
    --hours) read -r -a CASES <<<"$2"; shift ;;
    --repeat) REPEAT="$2"; shift ;;
    --ldh) LDH="$2"; shift ;;
    --work) WORK="$2"; shift ;;
    -h|--help) sed -n 2,19p "$0"; exit 0 ;;
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
# repeat_pair SRC DST COPIES: the pair in SRC (left.csv, right.csv) COPIES times over in DST, each
# copy starting one sample interval (0.01 s) after the previous copy's last time.
repeat_pair() {
  mkdir -p "$2"
  for side in left right; do
    awk -F, -v OFS=, '
      FNR == 1 { if (NR > 1) off = last + 0.01 - first; n = 0 }
      /^#/ || /^time_s/ { if (NR == FNR) print; next }
      { if (n++ == 0) first = $1; t = $1 + off; last = t; $1 = sprintf("%.4f", t); print }
    ' $(for _ in $(seq 1 "$3"); do echo "$1/$side.csv"; done) >"$2/$side.csv"
  done
  touch "$2/done"
}
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
printf '%-8s %12s %10s %10s %14s %8s\n' hours samples wall_s cpu_s peak_rss_mb load1
for h in "${CASES[@]}"; do
  sim="$WORK/sim-${h}h"
  label="$h"
  if [ "$h" = 168 ] && [ "$FROM_DAY" = 1 ]; then
    sim="$WORK/week-from-day"
    day="$WORK/sim-24h/H01"
    if [ ! -f "$day/truth.json" ]; then
      "$LDH" simulate --free-living --hours 24 --seed 52 --rate-hz 100 -o "$WORK/sim-24h" -j 1 >/dev/null
    fi
    [ -f "$sim/H01/done" ] || repeat_pair "$day" "$sim/H01" 7
    label="168=7x24"
  elif [ "$h" = 24 ] && [ "$FROM_HOUR" = 1 ]; then
    sim="$WORK/day-from-hour"
    hour="$WORK/sim-1h/H01"
    if [ ! -f "$hour/truth.json" ]; then
      "$LDH" simulate --free-living --hours 1 --seed 52 --rate-hz 100 -o "$WORK/sim-1h" -j 1 >/dev/null
    fi
    [ -f "$sim/H01/done" ] || repeat_pair "$hour" "$sim/H01" 24
    label="24=24x1"
  elif [ ! -f "$sim/H01/truth.json" ]; then
    rm -rf "$sim"
    "$LDH" simulate --free-living --hours "$h" --seed 52 --rate-hz 100 -o "$sim" -j 1 >/dev/null
  fi
  walls=(); cpus=(); rsss=(); loads=()
  for r in $(seq 1 "$REPEAT"); do
    out="$WORK/out-${h}h"
    rm -rf "$out"
    log="$WORK/time-${h}h-$r.txt"
    # the machine's 1-minute load average as each run starts (other jobs share the cores)
    loads+=("$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo nan)")
    if ! /usr/bin/time -v "$LDH" monitor "$sim/H01/left.csv" "$sim/H01/right.csv" -o "$out" -j 1 \
        >"$WORK/monitor-${h}h.log" 2>"$log"; then
      echo "ldh monitor failed on the ${h} h pair; see $log" >&2
      tail -n 30 "$log" >&2
      exit 1
    fi
    walls+=("$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$log" \
      | awk -F: '{ if (NF == 3) print $1*3600 + $2*60 + $3; else print $1*60 + $2 }')")
    cpus+=("$(awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} END {print u + s}' "$log")")
    rsss+=("$(awk -F': ' '/Maximum resident set size/ {print $2 / 1024}' "$log")")
  done
  printf '%-8s %12s %10.2f %10.2f %14.0f %8.2f\n' "$label" "$((h * 360000))" \
    "$(printf '%s\n' "${walls[@]}" | median)" "$(printf '%s\n' "${cpus[@]}" | median)" \
    "$(printf '%s\n' "${rsss[@]}" | median)" "$(printf '%s\n' "${loads[@]}" | median)"
  echo "  runs: wall ${walls[*]} s; cpu ${cpus[*]} s; load1 ${loads[*]}" >&2
done
