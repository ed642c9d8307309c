#!/usr/bin/env bash
# Path-tracer throughput on the Cornell box (scenes/cornell_diffuse.toml: 256 × 256,
# max_depth 64, 2 threads), timed as whole processes: the checked-out build, an earlier one,
# and (if `import mitsuba` works) Mitsuba 3's path tracer in its fast `llvm_ad_rgb` variant
# through bench/mitsuba_reference.py (JIT compile included, as a user meets it) and in its
# `scalar_rgb` variant (one ray at a time, as grinlight traces them), alternately RUNS times.
# Prints each one's median wall time, its samples a second, and the ratios of grinlight's to
# the earlier build's and to Mitsuba's.
#
#   bench/path_throughput.sh [REVISION] [RUNS] [SPP] [MITSUBA_SPP]
#
# Defaults: 9b345d5 (version 0.6.0), 3 runs, 256 samples a pixel (16 passes of 16; Mitsuba's
# scalar variant too), Mitsuba's fast variant 1024 (its run time is mostly the JIT's at fewer).
# The earlier build is made in a temporary git worktree into target/earlier. Mitsuba needs
# DRJIT_LIBLLVM_PATH (see mitsuba_reference.py).
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-9b345d5}
runs=${2:-3}
spp=${3:-256}
mitsuba_spp=${4:-1024}
scene=scenes/cornell_diffuse.toml
pixels=$((256 * 256))
cargo build --release --quiet --bin grinlight
source bench/earlier.sh
source bench/wall.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
mitsuba=no
if python3 -c 'import mitsuba' 2> /dev/null; then mitsuba=yes; fi
declare -A times
for ((i = 0; i < runs; i++)); do
    for build in earlier current; do
        bin=$(grinlight_of "$build")
        t=$(wall "$bin" render "$scene" --integrator path --spp 16 --passes $((spp / 16)) \
            --threads 2 -o "$out/$build.exr")
        times[$build]+="$t "
    done
    if [ $mitsuba = yes ]; then
        t=$(wall python3 bench/mitsuba_reference.py "$scene" "$out/mitsuba.exr" --spp "$mitsuba_spp")
        times[mitsuba]+="$t "
        t=$(wall python3 bench/mitsuba_reference.py "$scene" "$out/scalar.exr" --spp "$spp" \
            --variant scalar_rgb)
        times[scalar]+="$t "
    fi
done
rate() { awk "BEGIN { printf \"%.2f\", $1 * $pixels / $2 / 1e6 }"; }
printf "%-28s %10s %14s\n" build "median s" "M samples/s"
for build in earlier current mitsuba scalar; do
    [ -z "${times[$build]:-}" ] && continue
    m=$(echo ${times[$build]} | tr ' ' '\n' | median)
    n=$spp
    [ $build = mitsuba ] && n=$mitsuba_spp
    label=$build
    [ $build = earlier ] && label="earlier ($rev)"
    [ $build = mitsuba ] && label="Mitsuba 3 llvm_ad_rgb"
    [ $build = scalar ] && label="Mitsuba 3 scalar_rgb"
    printf "%-28s %10s %14s\n" "$label" "$m" "$(rate $n $m)"
    declare "rate_$build=$(rate $n $m)"
done
echo "current / earlier: $(awk "BEGIN { printf \"%.2f\", $rate_current / $rate_earlier }")×"
if [ $mitsuba = yes ]; then
    echo "current / Mitsuba: $(awk "BEGIN { printf \"%.2f\", $rate_current / $rate_mitsuba }")×"
    echo "current / Mitsuba scalar: $(awk "BEGIN { printf \"%.2f\", $rate_current / $rate_scalar }")×"
fi
