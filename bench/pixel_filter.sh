#!/usr/bin/env bash
# What a Gaussian pixel filter costs the path tracer: the Cornell box
# (scenes/cornell_diffuse.toml, 256 × 256) with its box filter and with Mitsuba's Gaussian
# (σ 0.5, r 2: what every imported Mitsuba scene has unless it says otherwise), one thread,
# user seconds, the checked-out build against an earlier one, alternately RUNS times. Prints
# each one's medians and the Gaussian's cost over the box.
#
#   bench/pixel_filter.sh [REVISION] [RUNS] [SPP]
#
# Defaults: cbb8adc (version 0.21.0), 5 runs, 16 samples a pixel.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-cbb8adc}
runs=${2:-5}
spp=${3:-16}
cargo build --release --quiet --bin grinlight
source bench/earlier.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
sed 's/^\[camera\]/[camera]\nfilter = "gaussian"\nfilter_stddev = 0.5\nfilter_radius = 2.0/' \
    scenes/cornell_diffuse.toml > "$out/gaussian.toml"
cp scenes/cornell_diffuse.toml "$out/box.toml"
user() { /usr/bin/time -f %U "$@" 2>&1 > /dev/null | tail -1; }
declare -A times
for ((i = 0; i < runs; i++)); do
    for build in earlier current; do
        bin=$(grinlight_of "$build")
        for filter in box gaussian; do
            t=$(user "$bin" render "$out/$filter.toml" --integrator path --spp "$spp" \
                --passes 1 --threads 1 -o "$out/$build-$filter.exr")
            times[$build-$filter]+="$t "
        done
    done
done
printf "%-22s %10s %14s %10s\n" build "box s" "gaussian s" "cost"
for build in earlier current; do
    b=$(echo ${times[$build-box]} | tr ' ' '\n' | median)
    g=$(echo ${times[$build-gaussian]} | tr ' ' '\n' | median)
    label=$build
    [ $build = earlier ] && label="earlier ($rev)"
    printf "%-22s %10s %14s %9s%%\n" "$label" "$b" "$g" "$(awk "BEGIN { printf \"%+.0f\", 100 * ($g / $b - 1) }")"
done
