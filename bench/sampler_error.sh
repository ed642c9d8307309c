#!/usr/bin/env bash
# The samplers on their own (`[render] sampler`): the checked-out build's error at equal
# samples with `stratified` (independent numbers, the film point and first vertex stratified
# over a pass) and `sobol` (Owen-scrambled Sobol points over every sample of a pixel), over
# SEEDS seeds, against a long reference in two halves rendered with the other sampler
# (`stratified`, seeds 9 and 10; examples/image_error: relative RMSE with the reference's own
# noise taken out), and each render's wall time. Prints each sampler's median RMSE and median
# time at each sample count, the ratio of the RMSEs and the ratio of the efficiencies
# 1/(RMSE² · time) (> 1: Sobol's image is cleaner at equal time).
#
#   bench/sampler_error.sh [SCENE] [INTEGRATOR] [SEEDS] [REFERENCE_PASSES]
#
# Defaults: the Cornell box, the path tracer, 5 seeds, 64 passes of 16 samples per half. The
# references are kept in target/bench-refs between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/cornell_diffuse.toml}
integrator=${2:-path}
seeds=${3:-5}
ref_passes=${4:-64}
cargo build --release --quiet --bin grinlight --example image_error
source bench/earlier.sh
source bench/wall.sh
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
bin=target/release/grinlight
error=target/release/examples/image_error
name=$(basename "$scene" .toml)
mkdir -p target/bench-refs
halves=()
for seed in 9 10; do
    ref=target/bench-refs/$name-$integrator-$ref_passes-$seed.exr
    if [ ! -f "$ref" ]; then
        "$bin" render "$scene" --integrator "$integrator" --sampler stratified --spp 16 \
            --passes "$ref_passes" --seed "$seed" -o "$out/ref.exr" > /dev/null 2>&1
        cp "$out/ref.exr" "$ref"
    fi
    halves+=("$ref")
done
printf "%-12s %6s %7s %12s %10s\n" sampler spp passes "median RMSE" "median s"
for shape in "16 1" "64 1" "16 4" "16 16"; do
    set -- $shape
    spp=$1 passes=$2
    declare -A median_of=() seconds_of=()
    for sampler in stratified sobol; do
        errors=() times=()
        for ((seed = 1; seed <= seeds; seed++)); do
            times+=("$(wall "$bin" render "$scene" --integrator "$integrator" --sampler "$sampler" \
                --spp "$spp" --passes "$passes" --seed "$seed" --threads 2 -o "$out/image.exr")")
            errors+=("$("$error" "$out/image.exr" "${halves[@]}" \
                | sed -E 's/.*relative RMSE ([0-9.]+).*/\1/' | tail -1)")
        done
        median_of[$sampler]=$(printf "%s\n" "${errors[@]}" | median)
        seconds_of[$sampler]=$(printf "%s\n" "${times[@]}" | median)
        printf "%-12s %6s %7s %12s %10s\n" "$sampler" "$spp" "$passes" "${median_of[$sampler]}" \
            "${seconds_of[$sampler]}"
    done
    awk -v e1="${median_of[sobol]}" -v e0="${median_of[stratified]}" \
        -v t1="${seconds_of[sobol]}" -v t0="${seconds_of[stratified]}" -v n=$((spp * passes)) \
        'BEGIN { printf "sobol / stratified at %d samples: RMSE %.3f, efficiency %.2f\n", n, e1 / e0, (e0 * e0 * t0) / (e1 * e1 * t1) }'
done
