#!/usr/bin/env bash
# Free flights under local majorants against the global one, in one run: the smoke plume
# (bench/smoke_plume.toml) rendered by the checked-out build and by an earlier one (a git revision whose
# free flights are drawn at the density's global maximum), each integrator RUNS times with
# the same seed; prints each one's median wall time, their ratio, and the ratio of the two
# images' means (1 within noise: both draws are exact).
#
#   bench/local_majorant.sh [REVISION] [RUNS]
#
# Defaults: e13bf03 (version 0.4.4), 3 runs. The earlier build is made in a temporary git
# worktree into target/earlier (kept: only the first run takes minutes). The last column is
# the checked-out build's own noise: its image at another seed against the one at seed 3.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-e13bf03}
runs=${2:-3}
mkdir -p bench/data
# The plume: density 30 exp(−r²/2w²) about the vertical axis through (0.1, ·, −0.2), w
# widening from 0.06 m at the floor to 0.2 m at the ceiling, over a haze of 0.01.
python3 - > bench/data/smoke_plume.txt << 'PY'
import math
nx, ny, nz = 48, 64, 48
print("# smoke plume density, x fastest, 48 x 64 x 48 nodes over [-1, 1]^3")
for k in range(nz):
    z = -1 + 2 * k / (nz - 1)
    for j in range(ny):
        y = -1 + 2 * j / (ny - 1)
        w = 0.06 + 0.07 * (y + 1)
        print(" ".join(
            "%.5g" % (0.01 + 30 * math.exp(-((-1 + 2 * i / (nx - 1) - 0.1) ** 2 + (z + 0.2) ** 2) / (2 * w * w)))
            for i in range(nx)))
PY
cargo build --release --quiet --bin grinlight --example image_error
source bench/earlier.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
earlier=$PWD/target/earlier/release/grinlight
source bench/wall.sh
printf "%-11s %12s %12s %7s   %-30s %s\n" integrator "$rev s" "now s" ratio \
    "now against the earlier" "now, seed 4 against seed 3"
for integrator in path photon_map; do
    times_old=() times_new=()
    for _ in $(seq "$runs"); do
        times_old+=("$(wall "$earlier" render bench/smoke_plume.toml \
            --integrator "$integrator" --seed 3 -o "$out/old.exr")")
        times_new+=("$(wall target/release/grinlight render bench/smoke_plume.toml \
            --integrator "$integrator" --seed 3 -o "$out/new.exr")")
    done
    old=$(printf "%s\n" "${times_old[@]}" | median)
    new=$(printf "%s\n" "${times_new[@]}" | median)
    target/release/grinlight render bench/smoke_plume.toml --integrator "$integrator" \
        --seed 4 -o "$out/noise.exr" > /dev/null 2>&1
    ratio_of() {
        target/release/examples/image_error "$1" "$2" "$2" | grep -o 'mean ratio [0-9.]*'
    }
    printf "%-11s %12s %12s %7s   %-30s %s\n" "$integrator" "$old" "$new" \
        "$(awk "BEGIN { printf \"%.2f\", $old / $new }")" "$(ratio_of "$out/new.exr" "$out/old.exr")" \
        "$(ratio_of "$out/noise.exr" "$out/new.exr")"
done
rm -rf "$out"
