"""What every elevation figure of scripts/figures.py shares: the front elevation (x–z
projection, mm) with the box outline and the sleeper, panel layout, saving.

The box spans 0..length in x and 0..height in z (the scene's box/, SI in the archive,
mm on the axes). The sleeper's bottom is not stored: it sits on the bed top under its
footprint (attribute bed_height) when the cycle starts and goes down by the sleeper
settlement of the moment drawn (0 before loading, settlement_peak at peak load,
permanent_settlement after unloading), so it is drawn to within the small overlap
with which it carries the preload.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

MM = 1e3  # metres to millimetres
LETTERS = "abcdefghijklmnopqrstuvwxyz"
STAGE_TITLES = {"before": "before loading", "peak": "at peak load", "after": "after unloading"}


def settlement_at(run, stage):
    """Sleeper settlement (m, downward positive) at a contact stage."""
    if stage == "before":
        return 0.0
    return float(run.attribute("settlement_peak" if stage == "peak" else "permanent_settlement"))


def peak_load_kn(run):
    return float(run.scene_value("sleeper", "peak_load")) / 1e3


def elevation(ax, run, settlement):
    """Front elevation of `run`'s box in mm: equal scale, box outline, the sleeper at
    the given settlement (m), and the vertical extent cut above the sleeper."""
    length = float(run.scene_value("box", "length")) * MM
    height = float(run.scene_value("box", "height")) * MM
    s_length = float(run.scene_value("sleeper", "length")) * MM
    s_height = float(run.scene_value("sleeper", "height")) * MM
    bottom = (float(run.attrs.get("bed_height", 0.0)) - settlement) * MM
    x0 = 0.5 * (length - s_length)
    ax.add_patch(Rectangle((0.0, 0.0), length, height, fill=False, lw=1.4, ec="black"))
    ax.add_patch(Rectangle((x0, bottom), s_length, s_height, fc="0.85", ec="black", lw=1.0,
                           hatch="//", zorder=5))
    ax.text(x0 + 0.5 * s_length, bottom + 0.5 * s_height, "sleeper", ha="center",
            va="center", fontsize=7, zorder=6, bbox=dict(fc="white", ec="none", pad=1))
    top = min(height, bottom + s_height) + 0.04 * length
    ax.set_xlim(-0.02 * length, 1.02 * length)
    ax.set_ylim(-0.03 * length, max(top, 0.3 * length))
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    ax.tick_params(labelsize=7)


def panels(count, title, columns=3):
    """A figure of `count` elevation panels, `columns` to a row, with a suptitle.
    "compressed" layout: constrained layout that also packs equal-aspect axes, so
    that the panel titles never run into the suptitle."""
    cols = max(1, min(count, columns))
    rows = -(-count // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.6 * cols, 4.8 * rows), squeeze=False,
                             layout="compressed")
    fig.suptitle(title, fontsize=10)
    axes = list(axes.flat)
    for ax in axes[count:]:
        fig.delaxes(ax)
    return fig, axes[:count]


def save(fig, out_dir, name):
    """Writes the figure as OUT_DIR/NAME.png, prints the path, returns it."""
    path = os.path.join(out_dir, name + ".png")
    if fig.get_layout_engine() is None:
        fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    print(f"wrote {path}")
    return path


def paper_note(values, fmt):
    """', paper: ...' for a title, or '' when the paper gives nothing."""
    return "" if values is None else "\npaper: " + fmt.format(*values)
