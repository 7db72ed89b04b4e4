#!/usr/bin/env bash
# Every benchmark of docs/benchmarks.md in one session, each beside its peer, logs in
# target/bench-logs/. Run from anywhere; takes ~25 min on 2 cores (add --scale for the
# 1 000 / 10 000-recording runs: +15 min and 2.5 GB of temporary disk).
#
#   bash data-fixtures/scripts/bench_all.sh [--scale]
#
# Peers: numpy/scipy ports (pipeline, Python API), nolds 0.6.2 (Lyapunov), scikit-learn (CV),
# installed into target/bench-venv with the versions printed at the top of the summary.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
logs=target/bench-logs
mkdir -p "$logs"
scale=${1:-}
summary="$logs/summary.txt"
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }

venv=target/bench-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q --upgrade pip
    "$venv/bin/pip" install -q maturin numpy scipy pandas scikit-learn "nolds==0.6.2" "setuptools<81"
fi
py="$venv/bin/python"
cargo build --release -p ldh-cli -q
"$venv/bin/maturin" build --release -q -m crates/ldh-py/Cargo.toml --target-dir target/maturin \
    -o target/bench-wheels --interpreter "$py" >/dev/null
"$py" -m pip install -q --force-reinstall target/bench-wheels/ldh-*.whl
ldh=target/release/ldh
say "== $(date -u +%FT%TZ) $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
say "   $("$py" -c 'import numpy, scipy, sklearn, nolds, importlib.metadata as m; print("numpy", numpy.__version__, "scipy", scipy.__version__, "scikit-learn", sklearn.__version__, "nolds", m.version("nolds"))')"

say "== criterion: per stage and end to end (cargo bench)"
for b in ldh-core:preprocess ldh-sim:pipeline ldh-core:lyapunov; do
    cargo bench -q -p "${b%%:*}" --bench "${b#*:}" -- --warm-up-time 1 --measurement-time 3 \
        >"$logs/criterion-${b#*:}.txt" 2>&1
    grep -E "time:" -B1 "$logs/criterion-${b#*:}.txt" | sed 's/^/   /' | tee -a "$summary" || true
done
RAYON_NUM_THREADS=1 cargo bench -q -p ldh-core --bench lyapunov -- --warm-up-time 1 \
    --measurement-time 3 lyap_r_n10000 >"$logs/criterion-lyapunov-1thread.txt" 2>&1
say "   (1 thread)"; grep -E "time:" "$logs/criterion-lyapunov-1thread.txt" | sed 's/^/   /' | tee -a "$summary" || true

say "== pipeline vs numpy/scipy port"
"$py" data-fixtures/scripts/bench_pipeline_python.py --repeats 5 2>&1 | tee "$logs/pipeline-python.txt" | tail -12 | sed 's/^/   /' | tee -a "$summary"

say "== Python API vs numpy/scipy port"
"$py" data-fixtures/scripts/bench_python_api.py --repeats 5 2>&1 | tee "$logs/python-api.txt" | tail -8 | sed 's/^/   /' | tee -a "$summary"

say "== Lyapunov: nolds 0.6.2"
"$py" data-fixtures/scripts/bench_lyapunov_nolds.py --sizes 1000,2000,5000,10000 --repeats 3 2>&1 \
    | tee "$logs/nolds.txt" | tail -10 | sed 's/^/   /' | tee -a "$summary"

say "== CV: ldh train vs scikit-learn on the same tables and folds"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
$ldh simulate --out "$tmp/c35" --healthy 15 --ldh 20 --seconds 30 --seed 11 --ldh-severity-min 0 >/dev/null 2>&1
$ldh analyze "$tmp/c35" --out "$tmp/a35" >/dev/null 2>&1
for jobs in 1 2; do
    t0=$(date +%s.%N)
    for task in three-class binary; do
        $ldh train --results "$tmp/a35" --task $task --out "$tmp/t-$task-$jobs" --jobs $jobs >/dev/null 2>&1
    done
    t1=$(date +%s.%N)
    say "   ldh train, both tasks, --jobs $jobs: $(echo "$t1 - $t0" | bc) s"
done
t0=$(date +%s.%N)
"$py" data-fixtures/scripts/sklearn_cv.py --seeds 1 --no-write >"$logs/sklearn.txt" 2>&1
t1=$(date +%s.%N)
say "   scikit-learn script, both tasks, one model seed: $(echo "$t1 - $t0" | bc) s"

say "== analyze: 1 vs 2 threads (100 subjects x 30 s, median of 3)"
$ldh simulate --out "$tmp/c100" --healthy 50 --ldh 50 --seconds 30 --seed 8 >/dev/null 2>&1
for jobs in 1 2; do
    ts=()
    for r in 1 2 3; do
        t0=$(date +%s.%N)
        $ldh analyze "$tmp/c100" --out "$tmp/o100" --jobs $jobs >/dev/null 2>&1
        t1=$(date +%s.%N)
        ts+=("$(echo "$t1 - $t0" | bc)")
    done
    say "   --jobs $jobs: $(printf '%s\n' "${ts[@]}" | sort -n | sed -n 2p) s (runs: ${ts[*]})"
done

say "== reports vs analysis (100 subjects)"
"$py" data-fixtures/scripts/bench_report.py --subjects 100 --repeats 3 2>&1 | sed 's/^/   /' | tee -a "$summary"

if [ "$scale" = "--scale" ]; then
    say "== scale: peak RSS and time at 1 000 and 10 000 recordings (--jobs 2)"
    for n in 500 5000; do
        h=$((n / 2))
        $ldh simulate --out "$tmp/s$n" --healthy $h --ldh $((n - h)) --seconds 30 --seed 4 >/dev/null 2>&1
        /usr/bin/time -f "   $((2 * n)) recordings: %e s wall, peak RSS %M kB" \
            $ldh analyze "$tmp/s$n" --out "$tmp/so$n" --jobs 2 2>&1 | grep recordings: | tee -a "$summary"
        rm -rf "$tmp/s$n" "$tmp/so$n"
    done
fi
say "== done $(date -u +%FT%TZ)"
