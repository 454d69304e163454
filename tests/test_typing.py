"""The package type-checks: mypy, with the settings of pyproject.toml ([tool.mypy]), finds no
error in src/rancf.  The cache (.mypy_cache at the repository root, as a plain ``mypy`` run uses)
keeps a re-run to a few seconds."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.skipif(
    importlib.util.find_spec("mypy") is None,
    reason="mypy is not installed (it is in the test extras: pip install -e .[test])",
)
def test_mypy_finds_no_error():
    run = subprocess.run(
        [sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Success: no issues found" in run.stdout, run.stdout


def test_few_type_ignores():
    """A ``type: ignore`` is the exception, each narrowed to an error code."""
    ignores = []
    for path in sorted((ROOT / "src" / "rancf").rglob("*.py")):
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if "type: ignore" in line:
                ignores.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert len(ignores) < 20, "\n".join(ignores)
    bare = [s for s in ignores if "type: ignore[" not in s]
    assert not bare, "\n".join(bare)
