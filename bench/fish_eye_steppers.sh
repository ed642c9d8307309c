#!/usr/bin/env bash
# The fish-eye scene (scenes/fish_eye.toml) rendered with its rays on their exact circles
# (`linearize`) and marched by RKN6(4) (`rkn`, adaptive at 1e-6), the same seed: wall time,
# curved steps, and the two images' relative RMSE and mean ratio — against the same between
# two seeds of `linearize` (the noise).
#
#   bench/fish_eye_steppers.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin grinlight --example image_error
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
sed 's/stepper = "linearize"/stepper = "rkn"/' scenes/fish_eye.toml > "$out/rkn.toml"
render() {
    target/release/grinlight render "$1" --seed "$2" -o "$3" 2>&1 \
        | grep -E "^rendered|curved marches" \
        | sed -E 's/.* in ([0-9.]+ s)$/\1/; s/.*curved marches ([0-9]+) \(([0-9]+) steps.*/\1 marches, \2 steps/' \
        | paste -sd ' ' -
}
printf "%-10s %s\n" stepper "wall time, curved marches and steps"
printf "%-10s %s\n" linearize "$(render scenes/fish_eye.toml 1 "$out/linearize.exr")"
printf "%-10s %s\n" rkn "$(render "$out/rkn.toml" 1 "$out/rkn.exr")"
render scenes/fish_eye.toml 2 "$out/seed2.exr" > /dev/null
compare() { target/release/examples/image_error "$1" "$2" "$2" | head -1 | sed 's/.*: //'; }
echo "rkn against linearize, seed 1:       $(compare "$out/rkn.exr" "$out/linearize.exr")"
echo "linearize, seed 2 against seed 1:    $(compare "$out/seed2.exr" "$out/linearize.exr")"
