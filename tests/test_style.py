"""The code base stays ruff-clean (configuration in pyproject.toml)."""

import os
import shutil
import subprocess
import sys

import pytest
from conftest import ROOT


def test_ruff_clean():
    ruff = shutil.which("ruff")
    if ruff is None:
        pytest.fail("ruff is part of the [test] extra; install it with pip install '.[test]'")
    result = subprocess.run(
        [ruff, "check", "src", "tests", "bench"], cwd=ROOT, capture_output=True, text=True
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_mass_path_does_not_import_heavy_libraries(tmp_path):
    """`plumbob mass part.stl` pays only for numpy: no shapely, manifold3d, trimesh or scipy."""
    code = (
        "import sys; from plumbob.cli import main; "
        f"main(['mass', {os.path.join(ROOT, 'shapes', 'block.toml')!r}, '--json']); "
        "heavy = [m for m in ('shapely', 'manifold3d', 'trimesh', 'scipy') if m in sys.modules]; "
        "sys.stderr.write(repr(heavy))"
    )
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stderr.strip().endswith("[]"), result.stderr
