#!/usr/bin/env bash
# Fish-eye rays followed by the renderer's tracer (the second table of
# examples/linearize_study: a fish-eye ball that is a scene's sphere, 2000 rays from inside it
# to the sphere, one thread) with the checked-out build and with an earlier one (a git
# revision's library under the checked-out study), alternately RUNS times: each build's median
# µs a ray with `linearize` and with `rkn` at 1e-6, and their ratio.
#
#   bench/linearize_in_renderer.sh [REVISION] [RUNS]
#
# Defaults: 6dc3d47 (version 0.4.5), 3 runs. The earlier build is made in a temporary git
# worktree into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-6dc3d47}
runs=${2:-3}
cargo build --release --quiet --example linearize_study
source bench/earlier.sh
earlier_worktree "$rev"
cp examples/linearize_study.rs "$worktree/examples/"
earlier_build --example linearize_study
for ((i = 0; i < runs; i++)); do
    for build in current earlier; do
        case $build in
            current) bin=target/release/examples/linearize_study ;;
            earlier) bin=target/earlier/release/examples/linearize_study ;;
        esac
        "$bin" renderer > "$out/table"
        awk '$1 == "linearize" { print $3 }' "$out/table" >> "$out/$build.linearize"
        awk '$1 == "rkn" && $2 == "1e-6" { print $3 }' "$out/table" >> "$out/$build.rkn"
    done
done
printf "%-10s %14s %14s %8s\n" build "linearize µs" "rkn 1e-6 µs" "ratio"
for build in earlier current; do
    l=$(median < "$out/$build.linearize")
    r=$(median < "$out/$build.rkn")
    printf "%-10s %14s %14s %8.1f\n" "$build" "$l" "$r" "$(awk "BEGIN { print $r / $l }")"
done
rm -rf "$out"
