#!/usr/bin/env bash
# Every shipped scene's render time, the checked-out build against an earlier one (a git
# revision), alternately RUNS times: both builds render the checked-out scenes/*.toml as
# shipped except for the passes and samples (PASSES passes of SPP samples a pixel), to a
# scratch EXR. Prints each scene's median
# wall time for both builds and their ratio; a scene the earlier build cannot read (a key it
# does not know) is marked "—", and a file that is not a scene to render (scenes/media.toml,
# media for `grinlight trace`) is left out.
#
#   bench/every_scene.sh [REVISION] [RUNS] [PASSES] [SPP] [SCENE,SCENE,…]
#
# Defaults: c7488ea (version 0.4.5), 3 runs, 1 pass of 1 sample; PASSES `own` renders each
# scene at its own passes and samples. The earlier build is made in a temporary git
# worktree into target/earlier.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-c7488ea}
runs=${2:-3}
passes=${3:-1}
spp=${4:-1}
only=${5:-}
cargo build --release --quiet --bin grinlight
source bench/earlier.sh
source bench/wall.sh
earlier_worktree "$rev"
earlier_build --bin grinlight
scenes=()
for scene in scenes/*.toml; do
    name=$(basename "$scene" .toml)
    if [[ -n "$only" && ",$only," != *",$name,"* ]]; then continue; fi
    if ! grep -q -e '^\[camera\]' -e '^\[\[receiver\]\]' "$scene"; then continue; fi
    scenes+=("$scene")
done
for ((i = 0; i < runs; i++)); do
    for scene in "${scenes[@]}"; do
        name=$(basename "$scene" .toml)
        for build in earlier current; do
            bin=$(grinlight_of "$build")
            if [[ $passes == own ]]; then flags=(); else flags=(--passes "$passes" --spp "$spp"); fi
            if t=$(wall "$bin" render "$scene" "${flags[@]}" -o "$out/$build.exr"); then
                echo "$t" >> "$out/$name.$build"
            else
                echo "$build failed on $name: $(tail -1 "$out/log")" >&2
            fi
        done
    done
done
echo "every scene, $passes pass(es) of $spp sample(s), medians of $runs alternating runs (s):"
printf "%-24s %10s %10s %8s\n" scene earlier current ratio
for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .toml)
    if [[ ! -s "$out/$name.current" ]]; then
        printf "%-24s %10s %10s %8s\n" "$name" "" "failed" ""
        continue
    fi
    now=$(median < "$out/$name.current")
    if [[ -s "$out/$name.earlier" ]]; then
        then=$(median < "$out/$name.earlier")
        printf "%-24s %10.2f %10.2f %8.3f\n" "$name" "$then" "$now" "$(awk "BEGIN { print $now / $then }")"
    else
        printf "%-24s %10s %10.2f %8s\n" "$name" "—" "$now" "—"
    fi
done
