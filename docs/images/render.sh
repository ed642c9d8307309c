#!/usr/bin/env bash
# Renders every shipped scene at its own settings, prints the time each takes (the table in
# docs/scenes.md), and copies its picture here: the PNG preview, a receiver's heat map for the
# fibers (the rod lens's picture is examples/chromatic_focus's), and the 1920 × 1080 views again
# at 480 × 270 for the page.
#
#   docs/images/render.sh            (from the repository's root, after `cargo build --release`)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/grinlight
out=$(mktemp -d)
here=docs/images
printf '| scene | seconds |\n|---|---|\n'
for scene in scenes/*.toml; do
    name=$(basename "$scene" .toml)
    [[ $name == media ]] && continue
    start=$EPOCHREALTIME
    "$bin" render "$scene" -o "$out/$name.exr" > "$out/$name.log" 2>&1
    end=$EPOCHREALTIME
    printf '| `%s` | %.1f |\n' "$name" "$(awk "BEGIN { print $end - $start }")"
    if [[ -f $out/$name.png ]]; then
        cp "$out/$name.png" "$here/$name.png"
    fi
done
for name in black_hole schwarzschild; do
    "$bin" render "scenes/$name.toml" --width 480 --height 270 -o "$out/$name-small.exr" > /dev/null 2>&1
    cp "$out/$name-small.png" "$here/$name.png"
done
cp "$out/fiber_led.exit.png" "$here/fiber_led.png"
cp "$out/diffusing_fiber.side.png" "$here/diffusing_fiber.png"
rm -rf "$out"
