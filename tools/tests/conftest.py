import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# The checks live in tools/vtk_checks.py; make them importable from the tests.
sys.path.insert(0, str(ROOT / "tools"))


@pytest.fixture(scope="session")
def fsim():
    """The release fsimFoam, built once per session (CARGO_TARGET_DIR honoured)."""
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "fsimFoam"], cwd=ROOT,
                   check=True)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "fsimFoam"
