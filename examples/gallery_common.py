"""Shared helpers of the gallery scripts: matplotlib with the Agg backend, the problem files,
saving every figure as PNG and SVG."""
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DEFAULT_OUT = ROOT / "docs" / "gallery"

plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 110, "font.size": 10, "axes.grid": True,
                     "grid.alpha": 0.3, "svg.hashsalt": "plateball", "legend.framealpha": 0.9})


def out_dir_from_argv():
    """The output directory: the first command-line argument, else docs/gallery."""
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_OUT
    out.mkdir(parents=True, exist_ok=True)
    return out


def save(fig, out_dir, name):
    """Writes NAME.png and NAME.svg (SVG without a date, so reruns give the same file)."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig.savefig(out_dir / f"{name}.png", bbox_inches="tight")
    fig.savefig(out_dir / f"{name}.svg", bbox_inches="tight", metadata={"Date": None})
    if not env_flag("PLATEBALL_GALLERY_KEEP_FIGURES"):  # the documentation's gallery collects them
        plt.close(fig)
    return [out_dir / f"{name}.png", out_dir / f"{name}.svg"]


def env_flag(name):
    return os.environ.get(name, "") not in ("", "0")
