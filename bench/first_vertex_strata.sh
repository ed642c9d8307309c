#!/usr/bin/env bash
# The first vertex's stratified numbers on their own: the path tracer's error at equal
# samples, the checked-out build against an earlier one that drew them independently, over
# SEEDS seeds and a few sample counts, against a long reference of the checked-out build in
# two halves (examples/image_error: relative RMSE with the reference's own noise taken out).
#
#   bench/first_vertex_strata.sh [REVISION] [SCENE] [SEEDS] [REFERENCE_PASSES]
#
# Defaults: the commit before the strata (655cbbc: independent numbers, the same integrator
# otherwise), the Cornell box, 4 seeds, 64 passes of 16 samples per half. Prints each build's
# median RMSE at 16 samples a pixel (one pass of 16) and at 64 (four passes of 16).
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-655cbbc}
scene=${2:-scenes/cornell_diffuse.toml}
seeds=${3:-4}
ref_passes=${4:-64}
cargo build --release --quiet --bin grinlight --example image_error
source bench/earlier.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
error=target/release/examples/image_error
name=$(basename "$scene" .toml)
halves=()
for seed in 9 10; do
    ref=bench/data/ref-$name-path-$ref_passes-$seed.exr
    if [ ! -f "$ref" ]; then
        target/release/grinlight render "$scene" --integrator path --spp 16 \
            --passes "$ref_passes" --seed "$seed" -o "$out/ref-$seed.exr" > /dev/null 2>&1
        cp "$out/ref-$seed.exr" "$ref"
    fi
    halves+=("$ref")
done
printf "%-26s %8s %14s\n" build spp "median RMSE"
for passes in 1 4; do
    for build in earlier current; do
        case $build in
            current) bin=target/release/grinlight label="checked out" ;;
            earlier) bin=target/earlier/release/grinlight label=$rev ;;
        esac
        errors=()
        for ((seed = 1; seed <= seeds; seed++)); do
            "$bin" render "$scene" --integrator path --spp 16 --passes "$passes" \
                --seed "$seed" -o "$out/$build.exr" > /dev/null 2>&1
            errors+=("$("$error" "$out/$build.exr" "${halves[@]}" \
                | sed -E 's/.*relative RMSE ([0-9.]+).*/\1/' | tail -1)")
        done
        m=$(printf "%s\n" "${errors[@]}" | median)
        printf "%-26s %8s %14s\n" "$build ($label)" $((16 * passes)) "$m"
    done
done
