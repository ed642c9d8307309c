#!/usr/bin/env bash
# Renders every shipped scene at its own settings, prints the time each takes, writes it into
# docs/scenes.md (each scene's "Time:" line, and the version and date in its header), and
# copies its picture here: the PNG preview, a receiver's heat map for the fibers (the rod
# lens's picture is examples/chromatic_focus's), and the 1920 × 1080 views again at 480 × 270
# for the page.
#
#   docs/images/render.sh            (from the repository's root, after `cargo build --release`;
#                                     Python 3 writes the times into docs/scenes.md)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/grinlight
out=$(mktemp -d)
here=docs/images
version=$("$bin" --version | awk '{print $2}')
times="$out/times.txt"
printf '| scene | seconds |\n|---|---|\n'
for scene in scenes/*.toml; do
    name=$(basename "$scene" .toml)
    [[ $name == media ]] && continue
    start=$EPOCHREALTIME
    "$bin" render "$scene" -o "$out/$name.exr" > "$out/$name.log" 2>&1
    end=$EPOCHREALTIME
    seconds=$(awk "BEGIN { printf \"%.1f\", $end - $start }")
    printf '| `%s` | %s |\n' "$name" "$seconds"
    echo "$name $seconds" >> "$times"
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
cp "$out/dyed_fiber.far_end.png" "$here/dyed_fiber.png"
python3 - "$times" "$version" "$(date -u +%Y-%m-%d)" <<'PY'
import re, sys
times = dict(line.split() for line in open(sys.argv[1]))
version, date = sys.argv[2], sys.argv[3]
path = "docs/scenes.md"
text = open(path).read()
text = re.sub(r"it takes \(versions? [^;]*?a 2-core machine", f"it takes (version {version}, {date}, a 2-core machine", text, count=1)
def section(m):
    name, body = m.group(1), m.group(2)
    if name in times:
        body = re.sub(r"Time: [0-9.]+ s( \(version [^)]*\))?", f"Time: {times[name]} s", body, count=1)
    return f"## `{name}`{body}"
text = re.sub(r"## `([a-z_]+)`(.*?)(?=\n## `|\Z)", section, text, flags=re.S)
open(path, "w").write(text)
# The same times as docs/performance.md's table of shipped scenes.
path = "docs/performance.md"
text = open(path).read()
head, rest = text.split("## Shipped scenes\n", 1)
body, tail = rest.split("\n`black_hole`, `schwarzschild`", 1)
rows = "".join(f"| `{name}` | {seconds} |\n" for name, seconds in sorted(times.items()))
body = (f"\nVersion {version}, {date}, a 2-core x86-64 machine with 24 GiB, each scene once at its own\n"
        "settings with 2 threads; reproduce with `docs/images/render.sh` (after `cargo build\n"
        "--release`), which prints this table and refreshes the pictures of [scenes.md](scenes.md):\n\n"
        "| scene | seconds |\n|---|---|\n" + rows)
open(path, "w").write(head + "## Shipped scenes\n" + body + "\n`black_hole`, `schwarzschild`" + tail)
PY
rm -rf "$out"
