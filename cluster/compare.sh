# Sourced by the opt-in scheduler tests (cluster/*/local-test.sh): renders two scenes once in
# one process and as N = 2 and 4 shards through a scheduler, checks the merged files equal the
# single run's byte for byte, and prints the wall times as a Markdown table.
#
# The sourcing script sets $GRINLIGHT (the binary), $work (a scratch directory), $cores, and
# defines `shards N OUT SCENE [render options]`, which renders SCENE as N shards and merges
# them into OUT/result.exr (and its PNG and receiver files), returning when that is done.

# The wall time of a command, in seconds.
seconds() {
    local t0 t1
    t0=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }'
}

# One scene: NAME SCENE "FILES TO COMPARE" [render options].
compare_scene() {
    local name=$1 scene=$2 files=$3
    shift 3
    local dir=$work/$name
    mkdir -p "$dir"
    local t1 tn
    t1=$(seconds "$GRINLIGHT" render "$scene" -o "$dir/one.exr" --threads 1 "$@")
    tn=$(seconds "$GRINLIGHT" render "$scene" -o "$dir/single.exr" --threads 0 "$@")
    for n in 2 4; do
        local out=$dir/shards-$n t same=yes
        t=$(seconds shards "$n" "$out" "$scene" "$@")
        for f in $files; do
            cmp -s "$dir/single.$f" "$out/result.$f" || same="NO ($f differs)"
        done
        [[ -e $out/result.${files%% *} ]] || same="NO (no result: see $out)"
        printf '| %s | %s | %s s | %s s | N = %s: %s s | %s |\n' "$name" "$*" "$t1" "$tn" "$n" "$t" "$same"
    done
}

# The table: its header names the scheduler ($1).
compare_all() {
    printf '\n| scene | work | one process, 1 thread | one process, %s threads | %s, N shards × 1 CPU | merged = single run |\n' "$cores" "$1"
    printf '|---|---|---|---|---|---|\n'
    compare_scene fiber "$repo/scenes/fiber_led.toml" "exit.csv exit.radial.csv" --receiver-photons 1000000
    compare_scene cornell "$repo/scenes/cornell_caustic.toml" "exr png" --passes 8
}
