"""The atlas of a paving in matplotlib, in the colours of `detach atlas`."""

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
