#!/usr/bin/env bash
# Loading and rendering a big mesh lens: the cube-sphere Luneburg lens of examples/mesh_scale
# (N cells a face, 12 N² triangles, binary PLY, 200 × 150) rendered by the checked-out build
# and by an earlier one (a git revision), alternately RUNS times, each size in a process of
# its own: the median PLY load + BVH build time, peak resident memory per triangle and render
# time; and the analytic lens's median render time (checked-out build) for the ratio
# (load + render) / analytic.
#
#   bench/mesh_build.sh [REVISION] [RUNS] [N,N,…]
#
# Defaults: 4f0b3ae (version 0.5.0, obvhs's PLOC build), 5 runs, N = 330 (1.3·10⁶ triangles).
# The earlier build is made in a temporary git worktree into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-4f0b3ae}
runs=${2:-5}
sizes=${3:-330}
cargo build --release --quiet --example mesh_scale
worktree=$(mktemp -d)
out=$(mktemp -d)
trap 'git worktree remove --force "$worktree"; rm -rf "$worktree" "$out"' EXIT
git worktree add --quiet --detach "$worktree" "$rev"
(cd "$worktree" && CARGO_TARGET_DIR="$OLDPWD/target/earlier" cargo build --release --quiet \
    --example mesh_scale)
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
field() { sed -nE "s/^$1=(.*)$/\1/p" "$2"; }
for ((i = 0; i < runs; i++)); do
    target/release/examples/mesh_scale --analytic > "$out/a"
    field render "$out/a" >> "$out/analytic"
    for n in ${sizes//,/ }; do
        for build in earlier current; do
            case $build in
                current) bin=target/release/examples/mesh_scale ;;
                earlier) bin=target/earlier/release/examples/mesh_scale ;;
            esac
            "$bin" --one "$n" > "$out/r"
            for k in triangles load peak render; do field $k "$out/r" >> "$out/$build.$n.$k"; done
        done
    done
done
analytic=$(median < "$out/analytic")
echo "analytic lens: render $analytic s (median of $runs)"
printf "%-9s %12s %16s %18s %12s %22s\n" build triangles "load + BVH (s)" "peak (B/triangle)" \
    "render (s)" "(load + render) / analytic"
for n in ${sizes//,/ }; do
    for build in earlier current; do
        load=$(median < "$out/$build.$n.load")
        render=$(median < "$out/$build.$n.render")
        printf "%-9s %12s %16.2f %18.1f %12.2f %22.2f\n" "$build" \
            "$(head -1 "$out/$build.$n.triangles")" "$load" "$(median < "$out/$build.$n.peak")" \
            "$render" "$(awk "BEGIN { print ($load + $render) / $analytic }")"
    done
done
