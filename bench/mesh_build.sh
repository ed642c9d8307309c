#!/usr/bin/env bash
# Loading and rendering a big mesh lens: the Luneburg lens of examples/mesh_scale bounded by
# a triangulated sphere (200 × 150), each case in a process of its own: the median load +
# BVH build time, peak resident memory per triangle and render time, and (load + render)
# over the analytic lens's median render time (checked-out build).
#
# The cube sphere of N cells a face (12 N² triangles, binary PLY) is rendered by the
# checked-out build and by an earlier one (a git revision) alternately RUNS times; then, by
# the checked-out build alone (examples/mesh_scale learnt these options after 0.5.0), the
# same spheres read from OBJ files and the icosphere split 8 times (1.3·10⁶ triangles).
#
#   bench/mesh_build.sh [REVISION] [RUNS] [N,N,…]
#
# Defaults: 4f0b3ae (version 0.5.0, obvhs's PLOC build), 3 runs, N = 330,913 (1.3·10⁶ and
# 10⁷ triangles; the 10⁷ OBJ file is ≈ 0.4 GB in out/ while it is read). The earlier build is
# made in a temporary git worktree into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-4f0b3ae}
runs=${2:-3}
sizes=${3:-330,913}
cargo build --release --quiet --example mesh_scale
source bench/earlier.sh
earlier_worktree "$rev"
earlier_build --example mesh_scale
current=target/release/examples/mesh_scale
earlier=target/earlier/release/examples/mesh_scale
field() { sed -nE "s/^$1=(.*)$/\1/p" "$2"; }
# measure LABEL BINARY ARGS…: one run, its fields appended to $out/LABEL.*
measure() {
    local label=$1 bin=$2
    shift 2
    "$bin" --one "$@" > "$out/r"
    for k in triangles load peak render; do field $k "$out/r" >> "$out/$label.$k"; done
}
rows=()
for ((i = 0; i < runs; i++)); do
    "$current" --analytic > "$out/a"
    field render "$out/a" >> "$out/analytic"
    for n in ${sizes//,/ }; do
        measure "earlier PLY cube $n" "$earlier" "$n"
        measure "current PLY cube $n" "$current" "$n"
    done
    for n in ${sizes//,/ }; do measure "current OBJ cube $n" "$current" "$n" --obj; done
    measure "current PLY ico 8" "$current" 8 --ico
done
for n in ${sizes//,/ }; do rows+=("earlier PLY cube $n" "current PLY cube $n"); done
for n in ${sizes//,/ }; do rows+=("current OBJ cube $n"); done
rows+=("current PLY ico 8")
analytic=$(median < "$out/analytic")
echo "analytic lens: render $analytic s (median of $runs); medians of $runs runs below"
printf "%-26s %10s %14s %18s %11s %20s\n" "build, file, sphere" triangles "load + BVH (s)" \
    "peak (B/triangle)" "render (s)" "(load + render) / analytic"
for label in "${rows[@]}"; do
    load=$(median < "$out/$label.load")
    render=$(median < "$out/$label.render")
    printf "%-26s %10s %14.2f %18.1f %11.2f %20.2f\n" "$label" \
        "$(head -1 "$out/$label.triangles")" "$load" "$(median < "$out/$label.peak")" \
        "$render" "$(awk "BEGIN { print ($load + $render) / $analytic }")"
done
