"""Shared fixtures: the repository's scenes and the command-line program the package is
compared with (built by `cargo test --release`, or here if missing)."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def scenes() -> Path:
    return ROOT / "scenes"


@pytest.fixture(scope="module")
def cli() -> Path:
    """The `grinlight` program of this checkout (GRINLIGHT_BIN, else target/release)."""
    given = os.environ.get("GRINLIGHT_BIN")
    if given:
        return Path(given)
    binary = ROOT / "target" / "release" / "grinlight"
    if not binary.exists():
        subprocess.run(["cargo", "build", "--release", "--bin", "grinlight"], cwd=ROOT, check=True)
    return binary


def run(cli: Path, *args, cwd: Path) -> subprocess.CompletedProcess:
    """Runs the program, failing with its output when it fails."""
    done = subprocess.run([str(cli), *map(str, args)], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr + done.stdout
    return done
