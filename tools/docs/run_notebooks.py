#!/usr/bin/env python3
"""Executes the notebooks of docs/notebooks/ (nbclient, the ipykernel of Debian's /usr/bin/python3)
and fails on the first cell that raises (each notebook checks its numbers with assert).

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/run_notebooks.py [NOTEBOOK.ipynb ...]

The notebooks run in memory, so the committed files keep no outputs."""
import pathlib
import sys
import time

import os

import nbformat
from nbclient import NotebookClient

ROOT = pathlib.Path(__file__).resolve().parents[2]
TIMEOUT_S = 120  # per cell: a cell of these notebooks takes seconds; a hang fails instead of blocking CI
os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger note about frozen modules


def main(paths):
    paths = [pathlib.Path(p) for p in paths] or sorted((ROOT / "docs" / "notebooks").glob("*.ipynb"))
    for path in paths:
        start = time.perf_counter()
        notebook = nbformat.read(path, as_version=4)
        NotebookClient(notebook, timeout=TIMEOUT_S, kernel_name="python3",
                       resources={"metadata": {"path": str(ROOT)}}).execute()
        print(f"{path.name}: {len(notebook.cells)} cells ran in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
