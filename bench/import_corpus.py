#!/usr/bin/env python3
"""Every scene file of another renderer in a directory through `grinlight convert`: converted
exactly, converted with --approximate (and what was approximated), or refused — by which
message. None may panic.

    python3 bench/import_corpus.py DIR [xml|pbrt]

The corpora used for docs/import.md: the mitsuba-data repository (Mitsuba 3's test and
documentation scenes, with its meshes and images: `git clone
https://github.com/mitsuba-renderer/mitsuba-data`), and pbrt-v4's scenes (`git clone
https://github.com/mmp/pbrt-v4-scenes`, `pbrt`; its files that are scenes of their own, with a
camera: files only included by others are left out). Give the directory.
"""
import collections
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "target", "release", "grinlight")


def convert(path, out, approximate):
    args = [EXE, "convert", path, "-o", out] + (["--approximate"] if approximate else [])
    r = subprocess.run(args, capture_output=True, text=True, timeout=120)
    if os.path.exists(out):
        os.remove(out)
    return r.returncode, r.stderr


def reason(stderr):
    """The refusal's words without the file and line, and with names and numbers generalised."""
    line = next((l for l in stderr.splitlines() if l.startswith("error:")), stderr.strip()[:200])
    line = re.sub(r"^error: \S+:\d+:\d+: ", "", line)
    line = re.sub(r"'[^']*'", "'…'", line)
    line = re.sub(r'id="[^"]*"', 'id="…"', line)
    line = re.sub(r'(MakeNamed\w+|NamedMaterial|Texture) "[^"]*"', r'\1 "…"', line)
    return line[:150]


def main():
    root = sys.argv[1]
    ext = "." + (sys.argv[2] if len(sys.argv) > 2 else "xml")
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(root) for f in fs if f.endswith(ext))
    if ext == ".pbrt":
        # A pbrt file included by others (geometry, materials) is no scene of its own.
        files = [f for f in files if re.search(r"^\s*Camera\b", open(f, errors="replace").read(), re.M)]
    outcome = collections.Counter()
    refusals = collections.Counter()
    approximations = collections.Counter()
    panics = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "s.toml")
        for path in files:
            code, err = convert(path, out, False)
            if code not in (0, 1) or "panicked" in err:
                panics.append(path)
            if code == 0:
                outcome["exact"] += 1
                continue
            code, err = convert(path, out, True)
            if code not in (0, 1) or "panicked" in err:
                panics.append(path)
            if code == 0:
                outcome["approximated"] += 1
                for l in err.splitlines():
                    if "approximated:" in l:
                        approximations[re.sub(r"^.*?\d+:\d+: ", "", l)[:110]] += 1
            else:
                outcome["refused"] += 1
                refusals[reason(err)] += 1
    print(f"{len(files)} scene files: " + ", ".join(f"{k} {v}" for k, v in outcome.most_common()) + f", panics {len(panics)}")
    print("\nrefused, by reason:")
    for r, n in refusals.most_common():
        print(f"{n:4}  {r}")
    print("\napproximations made:")
    for r, n in approximations.most_common():
        print(f"{n:4}  {r}")
    for p in panics:
        print("PANIC", p)
    sys.exit(1 if panics else 0)


if __name__ == "__main__":
    main()
