"""Atlases in matplotlib, in the colours of `detach atlas` and `detach
params --out`."""

from __future__ import annotations

import numpy as np


def plot_paving(paving, ax=None, legend=True):
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Patch

    from . import CLASSES, palette

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 5))
    leaves = paving.leaves
    colours = palette()
    shown = []
    for cls in CLASSES:
        part = leaves[leaves["cell"] == cls]
        if len(part) == 0:
            continue
        x0, x1 = part["theta_lo"], part["theta_hi"]
        y0, y1 = part["theta_dot_lo"], part["theta_dot_hi"]
        verts = np.stack(
            [np.stack([x0, y0], 1), np.stack([x1, y0], 1), np.stack([x1, y1], 1), np.stack([x0, y1], 1)],
            axis=1,
        )
        symbol, meaning, rgb = colours[cls]
        undefined = cls == "undefined"
        ax.add_collection(
            PolyCollection(
                verts,
                facecolors=rgb,
                edgecolors="#b02020" if undefined else "none",
                linewidths=0.0,
                hatch="////" if undefined else None,
            )
        )
        shown.append(
            Patch(
                facecolor=rgb,
                edgecolor="#b02020" if undefined else "#222222",
                hatch="////" if undefined else None,
                label=f"{symbol}: {meaning}",
            )
        )
    (t0, t1), (w0, w1) = paving.root
    ax.set_xlim(t0, t1)
    ax.set_ylim(w0, w1)
    ax.set_xlabel("θ (rad)")
    ax.set_ylabel("θ\u0307 (rad/s)")
    params = " ".join(f"{k}={v}" for k, v in paving.scene.params.items())
    note = "" if paving.complete else f" [{paving.stop_text}]"
    ax.set_title(f"{paving.scene.name} {params}{note}")
    if legend and shown:
        ax.legend(handles=shown, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return ax


def plot_param_atlas(atlas, ax=None, legend=True):
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Patch

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 5))
    b = atlas.bounds
    if b.shape[1] == 1:
        # one parameter: each box as a bar over [0, 1]
        b = np.concatenate([b, np.tile([[0.0, 1.0]], (len(b), 1, 1))], axis=1)
    classes = atlas._native.classes()
    codes = atlas._codes()[:, -1]
    shown = []
    for k, (text, rgb) in enumerate(classes):
        part = b[codes == k]
        if len(part) == 0:
            continue
        x0, x1, y0, y1 = part[:, 0, 0], part[:, 0, 1], part[:, 1, 0], part[:, 1, 1]
        verts = np.stack(
            [np.stack([x0, y0], 1), np.stack([x1, y0], 1), np.stack([x1, y1], 1), np.stack([x0, y1], 1)],
            axis=1,
        )
        ax.add_collection(PolyCollection(verts, facecolors=rgb, edgecolors="none", linewidths=0.0))
        shown.append(Patch(facecolor=rgb, edgecolor="#222222", label=text))
    root = atlas._native.root
    ax.set_xlim(*root[0])
    ax.set_xlabel(atlas.axes[0][0])
    if len(root) == 2:
        ax.set_ylim(*root[1])
        ax.set_ylabel(atlas.axes[1][0])
    else:
        ax.set_ylim(0.0, 1.0)
        ax.set_yticks([])
    note = "" if atlas.complete else " [box budget reached: coarser]"
    ax.set_title(f"{atlas.scene.name}: certified parameter atlas{note}")
    if legend and shown:
        ax.legend(handles=shown, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return ax


def plot_band(band, ax=None, color="black"):
    """A certified tube's boxes on the phase plane, as filled rectangles."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    if ax is None:
        _, ax = plt.subplots()
    t0, t1 = band["theta_lo"], band["theta_hi"]
    w0, w1 = band["theta_dot_lo"], band["theta_dot_hi"]
    quads = np.stack(
        [np.stack([t0, w0], 1), np.stack([t1, w0], 1), np.stack([t1, w1], 1), np.stack([t0, w1], 1)],
        1,
    )
    ax.add_collection(PolyCollection(quads, facecolors=color, edgecolors=color, linewidths=0.3))
    ax.autoscale_view()
    ax.set_xlabel("θ")
    ax.set_ylabel("θ̇")
    return ax


#: Fills of a reach paving's fates (0 reaches, 1 avoids, 2 undecided), the
#: colours of `detach reach --picture`.
REACH_COLOURS = ("#4477aa", "#f2f2ec", "#a0a0a0")


def plot_reach(reach, ax=None, legend=True):
    """A reach paving: each leaf filled by its fate (proved to reach the
    target, proved to avoid it, undecided)."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Patch

    if ax is None:
        _, ax = plt.subplots()
    leaves = reach.leaves
    t0, t1 = leaves["theta_lo"], leaves["theta_hi"]
    w0, w1 = leaves["theta_dot_lo"], leaves["theta_dot_hi"]
    quads = np.stack(
        [np.stack([t0, w0], 1), np.stack([t1, w0], 1), np.stack([t1, w1], 1), np.stack([t0, w1], 1)],
        1,
    )
    colours = [REACH_COLOURS[int(f)] for f in leaves["fate"]]
    ax.add_collection(PolyCollection(quads, facecolors=colours, edgecolors="none"))
    ax.autoscale_view()
    ax.set_xlabel("θ")
    ax.set_ylabel("θ̇")
    inner, outer = reach.area()
    note = "" if reach.complete else " [box budget reached: coarser]"
    ax.set_title(f"reaching states: area in [{inner:.6g}, {outer:.6g}]{note}")
    if legend:
        names = ("proved to reach", "proved to avoid", "undecided")
        ax.legend(handles=[Patch(facecolor=c, edgecolor="#222222", label=n)
                           for c, n in zip(REACH_COLOURS, names)],
                  loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return ax
