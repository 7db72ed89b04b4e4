#!/usr/bin/env bash
# Regenerates data-fixtures/cohort, the demo cohort compiled into ldh-core (crates/ldh-core/src/demo.rs):
# ten healthy people and three with LDH, 35 s each at 100 Hz with a 180-degree turn, seed 1
# (ldh_sim::demo::demo_cohort_params; the ldh-sim test `the_shipped_cohort_is_what_the_simulator_writes`
# fails until this is rerun after a change of the simulator or of those settings).
#
# Usage: bash data-fixtures/scripts/make_demo.sh [LDH_BINARY]
#   LDH_BINARY: an `ldh` built from this tree (default: `cargo run --profile ci -p ldh-cli --`).
# The manifest and cohort.json stay plain; each leg's CSV is stored as <side>.csv.gz (gzip -9n, no
# name or time in the header, so the bytes depend on the CSV alone); truth.json is not shipped.
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ $# -ge 1 ]; then ldh=("$1"); else ldh=(cargo run --quiet --locked --profile ci -p ldh-cli --); fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"${ldh[@]}" simulate --out "$tmp/cohort" --healthy 10 --ldh 3 --seconds 35 --seed 1
rm -rf data-fixtures/cohort
mkdir -p data-fixtures/cohort
cp "$tmp/cohort/manifest.csv" "$tmp/cohort/cohort.json" data-fixtures/cohort/
for d in "$tmp"/cohort/*/; do
    s="$(basename "$d")"
    mkdir -p "data-fixtures/cohort/$s"
    for side in left right; do
        gzip -9n -c "$d/$side.csv" > "data-fixtures/cohort/$s/$side.csv.gz"
    done
done
du -sb data-fixtures/cohort
