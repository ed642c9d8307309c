#!/usr/bin/env bash
# A volume caustic at equal time: grinlight's photon mapper, its path tracer and (if
# `import mitsuba` works) Mitsuba 3's volpath, each given the same seconds, against a long
# path-tracer reference made of two halves of different seeds (examples/image_error: relative
# RMSE per pixel and channel with the reference's own noise taken out, and mean ratios, over
# the image and over rectangles).
#
#   bench/volume_caustic_equal_time.sh [SECONDS] [REFERENCE_PASSES] [SCENE] [X0 Y0 X1 Y1]...
#
# Defaults: 30 s, 1024 passes per half, bench/volume_caustic_small_light.toml (64 × 64; a
# small area light in a snoot: the cone is found by a path tracer only through the ball, from
# the few phase samples that hit the light), its room below the lamp [0, 64) × [16, 64) and its
# cone [26, 38) × [48, 64) (another scene: the whole image and the rectangles given). The
# lamp's own pixels, a few of radiance 300 partly covered, weigh on every image's RMSE alike.
# The references are
# kept in bench/data/ref-<scene>-<passes>-{9,10}.exr (not in git) and reused.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
ref_passes=${2:-1024}
scene=${3:-bench/volume_caustic_small_light.toml}
region=("${@:4}")
if [ $# -lt 3 ]; then region=(0 16 64 64 26 48 38 64); fi
cargo build --release --quiet --bin grinlight --example image_error
bin=target/release/grinlight
error=target/release/examples/image_error
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
name=$(basename "$scene" .toml)
halves=()
for seed in 9 10; do
    ref=bench/data/ref-$name-$ref_passes-$seed.exr
    if [ ! -f "$ref" ]; then
        "$bin" render "$scene" --integrator path --passes "$ref_passes" --seed "$seed" \
            -o "$out/ref-$seed.exr" > /dev/null 2>&1
        cp "$out/ref-$seed.exr" "$ref"
    fi
    halves+=("$ref")
done
source bench/wall.sh
report() {
    echo "$1 ($2 s):"
    "$error" "$3" "${halves[@]}" "${region[@]}" | sed 's/^/  /'
}
for integrator in photon_map path; do
    t=$(wall "$bin" render "$scene" --integrator "$integrator" --time-budget "$seconds" \
        --seed 1 -o "$out/$integrator.exr")
    report "grinlight $integrator, $(grep -o '[0-9]* pass(es)' "$out/log" | head -1)" "$t" \
        "$out/$integrator.exr"
done
if python3 -c 'import mitsuba' 2> /dev/null; then
    # Mitsuba's samples in the same seconds, from a 64-sample run's rendering rate.
    python3 bench/mitsuba_reference.py "$scene" "$out/probe.exr" --spp 64 > "$out/probe.log"
    probe=$(sed -E 's/.*, ([0-9.]+) s rendering.*/\1/' "$out/probe.log")
    spp=$(awk "BEGIN { s = 64 * int($seconds / $probe + 0.5); print (s < 64 ? 64 : s) }")
    python3 bench/mitsuba_reference.py "$scene" "$out/mitsuba.exr" --spp "$spp" --seed 1000 \
        > "$out/mitsuba.log"
    t=$(sed -E 's/.*, ([0-9.]+) s rendering.*/\1/' "$out/mitsuba.log")
    report "Mitsuba 3 volpath, $spp spp" "$t" "$out/mitsuba.exr"
else
    echo "Mitsuba 3 not installed (pip install mitsuba): its run skipped"
fi
