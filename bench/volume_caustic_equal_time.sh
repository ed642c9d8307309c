#!/usr/bin/env bash
# The volume caustic at equal time: grinlight's photon mapper against its path tracer, each
# compared with a long path-tracer reference (relative RMSE per pixel and channel, and the
# mean ratio), on bench/volume_caustic.toml. Prints the lines of examples/reference_check.
#
#   bench/volume_caustic_equal_time.sh [REFERENCE_PASSES] [PHOTON_MAP_PASSES]   (defaults 3072, 16)
set -euo pipefail
cd "$(dirname "$0")/.."
ref_passes=${1:-3072}
pm_passes=${2:-16}
scene=bench/volume_caustic.toml
out=$(mktemp -d)
cargo build --release --quiet --bin grinlight --example reference_check
bin=target/release/grinlight
check=target/release/examples/reference_check
"$bin" render "$scene" --integrator path --passes "$ref_passes" --seed 9 -o "$out/reference.exr" > /dev/null 2>&1
pm=$("$check" "$scene" "$out/reference.exr" 16 "$pm_passes" photon_map | head -1)
echo "photon map:  $pm"
seconds=$(sed -E 's/.*, ([0-9.]+) s:.*/\1/' <<< "$pm")
# The path tracer's passes in the photon mapper's time, from a 64-pass run's rate.
probe=$("$check" "$scene" "$out/reference.exr" 16 64 path | head -1)
probe_seconds=$(sed -E 's/.*, ([0-9.]+) s:.*/\1/' <<< "$probe")
passes=$(awk "BEGIN { p = int(64 * $seconds / $probe_seconds + 0.5); print (p < 1 ? 1 : p) }")
echo "path tracer: $("$check" "$scene" "$out/reference.exr" 16 "$passes" path | head -1)"
rm -rf "$out"
