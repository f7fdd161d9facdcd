"""Shared fixtures of the Python binding tests: the built CLI, the problem files, running the CLI."""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PROBLEMS = pathlib.Path(os.environ.get("PLATEBALL_PROBLEMS", ROOT / "problems"))


def cli_path(name="plateball"):
    """The built tool next to PLATEBALL_CLI (set by ctest), else build/NAME."""
    cli = os.environ.get("PLATEBALL_CLI")
    base = pathlib.Path(cli).parent if cli else ROOT / "build"
    return base / name


@pytest.fixture(scope="session")
def problems():
    return PROBLEMS


@pytest.fixture(scope="session")
def run_cli(tmp_path_factory):
    """run_cli(tool, *args) -> the JSON document the tool wrote (on standard output or to --out)."""
    def run(tool, *args, out_file=False):
        exe = cli_path(tool)
        if not exe.exists():
            pytest.skip(f"{exe} is not built")
        args = [str(a) for a in args]
        if out_file:
            out = tmp_path_factory.mktemp("cli") / "out.json"
            subprocess.run([str(exe), *args, "--out", str(out)], check=True, capture_output=True, text=True)
            return json.loads(out.read_text())
        done = subprocess.run([str(exe), *args], check=True, capture_output=True, text=True)
        return json.loads(done.stdout)
    return run
