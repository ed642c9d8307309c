#!/usr/bin/env bash
# The glossy Cornell box (scenes/cornell_glossy.toml) against its diffuse twin
# (bench/cornell_glossy_twin.toml: the same box with the gold ball, the frosted ball and the
# plastic box made Lambertian) at equal passes: wall seconds of `grinlight render`, the two
# alternating, RUNS runs each; prints every run and the medians' ratio. Given a second
# grinlight binary (another version), runs it alike in the same loop.
#
#   bench/glossy_twin.sh [RUNS] [OTHER_GRINLIGHT]   (default 5 runs)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
other=${2:-}
cargo build --release --quiet --bin grinlight
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
seconds() { # binary scene -> wall seconds from the render's own report (each binary its own
  # output: a build marks what it writes and refuses to replace another's file)
  "$1" render "$2" -o "$out/$(echo "$1" | tr / _).exr" 2>&1 | sed -nE 's/^rendered .* in ([0-9.]+) s$/\1/p'
}
for ((i = 0; i < runs; i++)); do
  for bin in target/release/grinlight $other; do
    echo "$bin glossy $(seconds "$bin" scenes/cornell_glossy.toml)"
    echo "$bin twin $(seconds "$bin" bench/cornell_glossy_twin.toml)"
  done
done | tee "$out/runs.txt"
median() { # binary kind -> median seconds
  awk -v b="$1" -v k="$2" '$1 == b && $2 == k { print $3 }' "$out/runs.txt" | sort -n |
    awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
for bin in target/release/grinlight $other; do
  g=$(median "$bin" glossy)
  t=$(median "$bin" twin)
  echo "$bin: glossy $g s, twin $t s (medians of $runs), ratio $(awk "BEGIN { printf \"%.2f\", $g / $t }")"
done
