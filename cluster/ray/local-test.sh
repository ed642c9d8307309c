#!/usr/bin/env bash
# Opt-in: runs grinlight's Ray recipe for real on this machine (a local Ray: all its cores) and
# checks its result. Installs Ray into a virtual environment under /tmp (pip, ≈ 80 MB), then
# for each scene renders it once in one process and as N shards on Ray merged by the driver,
# checks the merged files equal the single run's byte for byte, and prints the wall times with
# the machine's core count. Not part of CI (it downloads Ray and takes a few minutes).
#
#   cluster/ray/local-test.sh
set -euo pipefail
repo=$(realpath "$(dirname "$0")/../..")
cores=$(nproc)
venv=/tmp/grinlight-ray-venv
if [[ ! -x $venv/bin/python ]]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "ray==2.*"
fi
(cd "$repo" && cargo build --release --quiet)
export GRINLIGHT=$repo/target/release/grinlight
work=$(mktemp -d /tmp/grinlight-ray.XXXXXX)
echo "Ray $("$venv/bin/python" -c 'import ray; print(ray.__version__)'), local, $cores cores"

seconds() {
    local t0 t1
    t0=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }'
}

printf '\n| scene | work | one process, 1 thread | one process, %s threads | Ray, N shards × 1 CPU (with Ray'"'"'s start) | merged = single run |\n' "$cores"
printf '|---|---|---|---|---|---|\n'
run_scene() {
    local name=$1 scene=$2 files=$3
    shift 3
    local dir=$work/$name
    mkdir -p "$dir"
    local t1 tn
    t1=$(seconds "$GRINLIGHT" render "$scene" -o "$dir/one.exr" --threads 1 "$@")
    tn=$(seconds "$GRINLIGHT" render "$scene" -o "$dir/single.exr" --threads 0 "$@")
    for n in 2 4; do
        local out=$dir/ray-$n t same=yes
        t=$(seconds "$venv/bin/python" "$repo/cluster/ray/driver.py" "$scene" "$n" "$out" "$@")
        for f in $files; do
            cmp -s "$dir/single.$f" "$out/result.$f" || same="NO ($f differs)"
        done
        printf '| %s | %s | %s s | %s s | N = %s: %s s | %s |\n' "$name" "$*" "$t1" "$tn" "$n" "$t" "$same"
    done
}
run_scene fiber "$repo/scenes/fiber_led.toml" "exit.csv exit.radial.csv" --receiver-photons 1000000
run_scene cornell "$repo/scenes/cornell_caustic.toml" "exr png" --passes 8
echo
echo "machine: $cores cores; at most $cores shards run at once here. Ray's own start (a few"
echo "seconds) is in its times. work files: $work"
