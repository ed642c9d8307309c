#!/usr/bin/env bash
# Every test of grinlight: the library's and the program's (cargo test --release), then the
# Python package's (pytest), the package built from this checkout by pip and maturin into
# .venv (created here; its packages come from PyPI). Needs Python 3.9 or newer with venv.
set -euo pipefail
cd "$(dirname "$0")"
cargo test --release
python="${PYTHON:-python3}"
if ! "$python" -c 'import sys, venv; assert sys.version_info >= (3, 9)' 2>/dev/null; then
    echo "error: the Python package's tests need Python 3.9 or newer with its venv module" \
         "(set PYTHON to one)" >&2
    exit 1
fi
[ -x .venv/bin/python ] || "$python" -m venv .venv
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet ".[test]"
# The binary the Rust tests built, wherever cargo put it (CARGO_TARGET_DIR, relative to here).
target="${CARGO_TARGET_DIR:-target}"
case "$target" in /*) ;; *) target="$PWD/$target" ;; esac
GRINLIGHT_BIN="$target/release/grinlight" .venv/bin/python -m pytest -q python/tests
