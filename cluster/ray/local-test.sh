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

# Renders a scene as N shards on Ray and merges them (the driver does both).
shards() {
    local n=$1 out=$2 scene=$3
    shift 3
    "$venv/bin/python" "$repo/cluster/ray/driver.py" "$scene" "$n" "$out" "$@"
}

source "$repo/cluster/compare.sh"
compare_all "Ray (with Ray's start)"
echo
echo "machine: $cores cores; at most $cores shards run at once here. Ray's own start (a few"
echo "seconds) is in its times. work files: $work"
