"""Shared fixtures: the repository's fixtures folder and the `sightline` command built from the
same crate (the Python results are held to the command's)."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"


@pytest.fixture(scope="session")
def cli():
    """Runs the `sightline` command (SIGHTLINE_BIN, or target/release/sightline as
    `cargo test --release` leaves it) and returns its stdout as bytes."""
    path = pathlib.Path(os.environ.get("SIGHTLINE_BIN", ROOT / "target" / "release" / "sightline"))
    if not path.exists():
        pytest.fail(f"{path} not found: run `cargo build --release` first (or set SIGHTLINE_BIN)")

    def run(*args):
        done = subprocess.run([str(path), *map(str, args)], capture_output=True, check=True)
        return done.stdout

    return run
