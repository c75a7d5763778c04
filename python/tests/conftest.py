"""Shared fixtures: the ccdsim binary, built from this checkout when needed."""

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def ccdsim_binary() -> Path:
    """The ccdsim CLI of this checkout, built by cargo if it is missing or stale.

    It is built as `cargo test --workspace` builds it (the test profile, which is the dev
    profile, and the whole workspace's features), so after `scripts/test`'s Rust suite this is
    a no-op."""
    subprocess.run(
        ["cargo", "build", "--quiet", "--locked", "--profile", "test", "--workspace",
         "--bin", "ccdsim"],
        cwd=ROOT,
        check=True,
    )
    target = subprocess.run(
        [str(ROOT / "scripts/target-dir")], capture_output=True, text=True, check=True
    ).stdout.strip()
    path = Path(target) / "debug" / "ccdsim"
    assert path.exists(), f"cargo built no binary at {path}"
    return path
