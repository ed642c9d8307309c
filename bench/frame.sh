#!/usr/bin/env bash
# A frame's memory and output time: the 1920 × 1080 black hole (scenes/black_hole.toml, traced:
# --no-table, 1 sample a pixel) rendered by the checked-out build and by an earlier one (a git
# revision), alternately RUNS times: each build's median wall time, the part of it after the
# camera pass (assembling the film and writing the EXR and PNG: the wall time less the
# render's own "rendered in" time) and its peak resident memory.
#
#   bench/frame.sh [REVISION] [RUNS]
#
# Defaults: ac81a4a (version 0.4.6 before the film was reused), 3 runs; 7987c62 is the
# first build (which knows no deflection table and always traces). The earlier build is
# made in a temporary git worktree into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-ac81a4a}
runs=${2:-3}
cargo build --release --quiet --bin grinlight
source bench/earlier.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
for ((i = 0; i < runs; i++)); do
    for build in earlier current; do
        bin=$(grinlight_of "$build")
        # Builds from before the deflection table always trace: they have no --no-table.
        flags=(--spp 1)
        if "$bin" render --help | grep -q -- --no-table; then flags+=(--no-table); fi
        /usr/bin/time -f "%e %M" -o "$out/time" "$bin" render scenes/black_hole.toml \
            "${flags[@]}" -o "$out/$build.exr" > "$out/log" 2>&1
        read -r wall kb < "$out/time"
        rendered=$(sed -nE 's/^rendered .* in ([0-9.]+) s$/\1/p' "$out/log")
        echo "$wall" >> "$out/$build.wall"
        awk "BEGIN { print $wall - $rendered }" >> "$out/$build.output"
        echo "$kb" >> "$out/$build.peak"
    done
done
printf "%-9s %10s %16s %14s\n" build "wall (s)" "after pass (s)" "peak (MB)"
for build in earlier current; do
    printf "%-9s %10s %16.2f %14.0f\n" "$build" "$(median < "$out/$build.wall")" \
        "$(median < "$out/$build.output")" "$(awk "BEGIN { print $(median < "$out/$build.peak") / 1024 }")"
done
