"""Regenerates the whole gallery (the paper's Figures 2, 3, 6, 7, 8 and the convergence chart) as
PNG and SVG, from the library through the Python bindings:

    PYTHONPATH=build/python /usr/bin/python3 examples/make_gallery.py [--out DIR]   (default docs/gallery)
"""
import argparse
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import convergence_chart  # noqa: E402
import figure2_phase_portrait  # noqa: E402
import figure3_angles  # noqa: E402
import figure6_heading_pendulum  # noqa: E402
import figure7_isoparallel  # noqa: E402
import figure8_reach  # noqa: E402
from gallery_common import DEFAULT_OUT  # noqa: E402

SCRIPTS = [figure2_phase_portrait, figure3_angles, figure6_heading_pendulum, figure7_isoparallel, figure8_reach,
           convergence_chart]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=DEFAULT_OUT, help="output directory")
    args = parser.parse_args()
    start = time.perf_counter()
    for script in SCRIPTS:
        t0 = time.perf_counter()
        files = script.make(args.out)
        for f in files:
            if not f.exists() or f.stat().st_size == 0:
                raise SystemExit(f"make_gallery: {f} was not written")
        print(f"{script.__name__}: {', '.join(f.name for f in files)} ({time.perf_counter() - t0:.2f} s)")
    print(f"gallery: {len(SCRIPTS)} figures in {args.out} ({time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
