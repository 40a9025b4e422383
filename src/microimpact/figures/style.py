"""Shared look of the package's figures: journal single-column size, colorblind-safe colours.

Colours are the Okabe & Ito (2008) palette, safe for the common colour-vision
deficiencies; every series also gets its own line style so that the figures
survive grey-scale printing.
"""

from __future__ import annotations

import contextlib
import os

from .._optional import require

__all__ = [
    "FIGSIZE",
    "DPI",
    "COLORS",
    "LINESTYLES",
    "MARKERS",
    "series_style",
    "style",
    "new_axes",
    "pyplot",
    "shade_large_strain",
]

#: Single-column journal figure [in].
FIGSIZE = (3.5, 2.8)
#: Raster resolution [dpi].
DPI = 300

#: Okabe-Ito colours (black, vermillion, blue, bluish green, orange, reddish purple, sky blue).
COLORS = ["#000000", "#D55E00", "#0072B2", "#009E73", "#E69F00", "#CC79A7", "#56B4E9"]
#: Line styles, one per series, so that figures survive grey-scale printing.
LINESTYLES = ["-", "--", "-.", ":", (0, (5, 1.5, 1, 1.5, 1, 1.5)), (0, (8, 2))]
#: Markers, one per series of measured points.
MARKERS = ["o", "s", "^", "D", "v", "P"]

_RC = {
    "font.size": 8,
    "axes.labelsize": 8,
    "axes.titlesize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 6.5,
    "legend.frameon": False,
    "legend.handlelength": 2.6,
    "lines.linewidth": 1.2,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "hatch.linewidth": 0.4,
    "savefig.dpi": DPI,
    "svg.fonttype": "none",
}


def pyplot():
    """``matplotlib.pyplot``, with the Agg backend when there is no display."""
    mpl = require("matplotlib", "plotting")
    if not os.environ.get("DISPLAY") and not os.environ.get("MPLBACKEND"):
        with contextlib.suppress(Exception):
            mpl.use("Agg")
    return require("matplotlib.pyplot", "plotting")


@contextlib.contextmanager
def style():
    """Context manager applying the package's rc settings."""
    plt = pyplot()
    with plt.rc_context(_RC):
        yield plt


def new_axes(ax=None, figsize=FIGSIZE):
    """``ax`` itself, or the Axes of a new figure of ``figsize`` [in] (constrained layout)."""
    if ax is not None:
        return ax
    plt = pyplot()
    fig = plt.figure(figsize=figsize, layout="constrained")
    return fig.add_subplot()


def series_style(i: int) -> dict:
    """Colour and line style of the ``i``-th series."""
    return {"color": COLORS[i % len(COLORS)], "linestyle": LINESTYLES[i % len(LINESTYLES)]}


def shade_large_strain(ax, start, stop=None, *, label=True, text_xy=(0.985, 0.975), ha="right"):
    """Lightly hatch ``start <= x <= stop`` (default: to the right edge): ``a*/R* > 0.3``.

    The model assumes small strain; results in this band are outside it.
    Returns the patch (or ``None`` if ``start`` is beyond the axis).
    """
    lo, hi = ax.get_xlim()
    stop = hi if stop is None else stop
    if not start < stop:
        return None
    patch = ax.axvspan(start, stop, facecolor="none", edgecolor="0.82", hatch="//////", linewidth=0, zorder=0)
    if label:
        ax.text(
            *text_xy, r"$a^*/R^* > 0.3$", transform=ax.transAxes, ha=ha, va="top", fontsize=6, color="0.4", zorder=5
        )
    ax.set_xlim(lo, hi)
    return patch
