#!/usr/bin/env bash
# A scene with scattering media at equal time: grinlight's photon mapper, its path tracer and
# (if `import mitsuba` works) Mitsuba 3's volpath, each given the same seconds, against a long
# reference made of two halves of different seeds (examples/image_error: relative RMSE per
# pixel and channel with the reference's own noise taken out, and mean ratios, over the image
# and over rectangles), and a table of each image RMSE over Mitsuba's.
#
#   [REFERENCE=mitsuba] bench/volume_caustic_equal_time.sh [SECONDS[,SECONDS...]] [REFERENCE_PASSES]
#                                                          [SCENE] [X0 Y0 X1 Y1]...
#
# Defaults: 30 s, 1024 passes per half, bench/volume_caustic_small_light.toml (64 × 64; a
# small area light in a snoot: the cone is found by a path tracer only through the ball, from
# the few phase samples that hit the light), its room below the lamp [0, 64) × [16, 64) and its
# cone [26, 38) × [48, 64) (another scene: the whole image and the rectangles given). The
# lamp's own pixels, a few of radiance 300 partly covered, weigh on every image's RMSE alike.
# Several budgets, comma-separated, are run one after the other on the same references.
# The reference is grinlight's path tracer (REFERENCE_PASSES passes a half), or with
# REFERENCE=mitsuba Mitsuba 3's volpath (REFERENCE_PASSES samples a pixel a half, seeds
# 100000 and 200000, far from the equal-time run's 1000). The references are kept in
# bench/data/ref-<scene>-<passes>-{9,10}.exr and ref-<scene>-mitsuba-<spp>-{100000,200000}.exr
# (not in git) and reused.
#
# The fogged Cornell box of docs/performance.md: REFERENCE=mitsuba
# bench/volume_caustic_equal_time.sh 30,120 24576 bench/cornell_fog.toml
set -euo pipefail
cd "$(dirname "$0")/.."
IFS=, read -ra budgets <<< "${1:-30}"
ref_passes=${2:-1024}
scene=${3:-bench/volume_caustic_small_light.toml}
region=("${@:4}")
if [ $# -lt 3 ]; then region=(0 16 64 64 26 48 38 64); fi
reference=${REFERENCE:-grinlight}
mitsuba=false
if python3 -c 'import mitsuba' 2> /dev/null; then mitsuba=true; fi
cargo build --release --quiet --bin grinlight --example image_error
bin=target/release/grinlight
error=target/release/examples/image_error
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
name=$(basename "$scene" .toml)
halves=()
case $reference in
    grinlight)
        for seed in 9 10; do
            ref=bench/data/ref-$name-$ref_passes-$seed.exr
            if [ ! -f "$ref" ]; then
                "$bin" render "$scene" --integrator path --passes "$ref_passes" --seed "$seed" \
                    -o "$out/ref-$seed.exr" > /dev/null 2>&1
                cp "$out/ref-$seed.exr" "$ref"
            fi
            halves+=("$ref")
        done ;;
    mitsuba)
        $mitsuba || { echo "REFERENCE=mitsuba needs Mitsuba 3 (pip install mitsuba)"; exit 1; }
        for seed in 100000 200000; do
            ref=bench/data/ref-$name-mitsuba-$ref_passes-$seed.exr
            if [ ! -f "$ref" ]; then
                python3 bench/mitsuba_reference.py "$scene" "$out/ref-$seed.exr" \
                    --spp "$ref_passes" --seed "$seed" > /dev/null
                cp "$out/ref-$seed.exr" "$ref"
            fi
            halves+=("$ref")
        done ;;
    *) echo "REFERENCE is grinlight or mitsuba, not $reference"; exit 1 ;;
esac
echo "reference: $reference, ${halves[*]}"
source bench/wall.sh
# report LABEL SECONDS IMAGE: its errors; the whole image's relative RMSE is kept in $rmse,
# the seconds in $took.
report() {
    echo "$1 ($2 s):"
    took=$2
    "$error" "$3" "${halves[@]}" "${region[@]}" > "$out/error"
    sed 's/^/  /' "$out/error"
    rmse=$(sed -nE '1s/.*relative RMSE ([0-9.]+).*/\1/p' "$out/error")
}
summary=()
for seconds in "${budgets[@]}"; do
    declare -A rmse_of=() took_of=()
    for integrator in photon_map path; do
        t=$(wall "$bin" render "$scene" --integrator "$integrator" --time-budget "$seconds" \
            --seed 1 -o "$out/$integrator.exr")
        report "grinlight $integrator, $(grep -o '[0-9]* pass(es)' "$out/log" | head -1)" "$t" \
            "$out/$integrator.exr"
        rmse_of[$integrator]=$rmse
        took_of[$integrator]=$took
    done
    if $mitsuba; then
        # Mitsuba's samples in the same seconds, from a 64-sample run's rendering rate.
        python3 bench/mitsuba_reference.py "$scene" "$out/probe.exr" --spp 64 > "$out/probe.log"
        probe=$(sed -E 's/.*, ([0-9.]+) s rendering.*/\1/' "$out/probe.log")
        spp=$(awk "BEGIN { s = 64 * int($seconds / $probe + 0.5); print (s < 64 ? 64 : s) }")
        python3 bench/mitsuba_reference.py "$scene" "$out/mitsuba.exr" --spp "$spp" \
            --seed 1000 > "$out/mitsuba.log"
        t=$(sed -E 's/.*, ([0-9.]+) s rendering.*/\1/' "$out/mitsuba.log")
        report "Mitsuba 3 volpath, $spp spp" "$t" "$out/mitsuba.exr"
        summary+=("$(awk -v s="$seconds" -v p="${rmse_of[photon_map]}" -v q="${rmse_of[path]}" \
            -v m="$rmse" -v tp="${took_of[photon_map]}" -v tq="${took_of[path]}" -v tm="$took" \
            'BEGIN { printf "| %s | %.4f (%.1f s) | %.4f (%.1f s) | %.4f (%.1f s) | %.2f | %.2f |",
                     s, p, tp, q, tq, m, tm, p / m, q / m }')")
    else
        echo "Mitsuba 3 not installed (pip install mitsuba): its run skipped"
    fi
    unset rmse_of took_of
done
if [ ${#summary[@]} -gt 0 ]; then
    echo
    echo "whole-image relative RMSE at equal time (each run's seconds: Mitsuba's are estimated"
    echo "from a 64-sample probe, so they may differ from the budget a little)"
    echo "| s | photon map | path | Mitsuba volpath | photon map / Mitsuba | path / Mitsuba |"
    echo "|---|---|---|---|---|---|"
    printf '%s\n' "${summary[@]}"
fi
