"""Shared helpers: the repository, and the `detach` binary built from it."""

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def detach_bin():
    """The CLI built from this checkout (`cargo build --release`), or
    $DETACH_BIN."""
    path = pathlib.Path(os.environ.get("DETACH_BIN", REPO / "target" / "release" / "detach"))
    if not path.is_file():
        pytest.fail(f"{path} is missing: run `cargo build --release` first (or set DETACH_BIN)")
    return str(path)


def run_cli(*args, check=True):
    """Runs the CLI; returns (exit code, stdout, stderr)."""
    p = subprocess.run([detach_bin(), *args], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"detach {' '.join(args)} failed: {p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_json(*args):
    return json.loads(run_cli(*args)[1])
