#!/usr/bin/env bash
# 64 lights at equal time: the light sampler (one light a vertex, drawn by a bound on the
# irradiance it can send there) against an earlier build that sampled every light at every
# vertex, both integrators, each given the same seconds, against a long path-tracer reference
# made of two halves of different seeds (examples/image_error: relative RMSE with the
# reference's own noise taken out, and the mean ratio).
#
#   bench/many_lights.sh [REVISION] [SECONDS] [REFERENCE_PASSES]
#
# Defaults: 9b345d5 (version 0.6.0, every light at every vertex), 10 s, 2048 passes per half
# of bench/many_lights.toml. The references are kept in bench/data/ref-many_lights-<passes>-
# {9,10}.exr (not in git) and reused; the earlier build is made in a temporary git worktree
# into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-9b345d5}
seconds=${2:-10}
ref_passes=${3:-2048}
scene=bench/many_lights.toml
cargo build --release --quiet --bin grinlight --example image_error
source bench/earlier.sh
source bench/wall.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
error=target/release/examples/image_error
halves=()
for seed in 9 10; do
    ref=bench/data/ref-many_lights-$ref_passes-$seed.exr
    if [ ! -f "$ref" ]; then
        target/release/grinlight render "$scene" --integrator path --passes "$ref_passes" \
            --seed "$seed" -o "$out/ref-$seed.exr" > /dev/null 2>&1
        cp "$out/ref-$seed.exr" "$ref"
    fi
    halves+=("$ref")
done
for integrator in path photon_map; do
    for build in earlier current; do
        case $build in
            current) bin=target/release/grinlight label="checked out" ;;
            earlier) bin=target/earlier/release/grinlight label=$rev ;;
        esac
        t=$(wall "$bin" render "$scene" --integrator "$integrator" --time-budget "$seconds" \
            --seed 1 -o "$out/$build-$integrator.exr")
        echo "$build ($label) $integrator, $(grep -o '[0-9]* pass(es)' "$out/log" | head -1), $t s:"
        "$error" "$out/$build-$integrator.exr" "${halves[@]}" | sed 's/^/  /'
    done
done
