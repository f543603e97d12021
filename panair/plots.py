"""Matplotlib pictures of a panel mesh and of surface Cp.  Numeric-only.

Each function returns the figure, draws into ``ax`` if given, and saves to
``filename`` if given (the pattern of ``ironbark_opt`` plots).
"""
from __future__ import annotations

import numpy as np

__all__ = ["plot_mesh", "plot_cp"]


def _axes3d(ax):
    import matplotlib
    if ax is None:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=(10, 4))
        ax = fig.add_subplot(projection="3d")
    del matplotlib
    return ax.figure, ax


def _equal(ax, pts):
    lo, hi = pts.min(0), pts.max(0)
    c, h = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - h, c[0] + h)
    ax.set_ylim(c[1] - h, c[1] + h)
    ax.set_zlim(c[2] - h, c[2] + h)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")


def plot_mesh(corners, *, wake_corners=None, ax=None, filename=None, title="panel mesh"):
    """Wireframe of the panels (and wakes, dashed).

    Parameters
    ----------
    corners : ndarray (n, 4, 3) [m]
    wake_corners : ndarray (w, 4, 3) [m], optional
    ax : 3-D matplotlib axes, optional
    filename : str or path, optional
    title : str
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    fig, ax = _axes3d(ax)
    ax.add_collection3d(Poly3DCollection(list(corners), facecolor="0.85", edgecolor="k",
                                         linewidths=0.2))
    if wake_corners is not None and len(wake_corners):
        ax.add_collection3d(Poly3DCollection(list(wake_corners), facecolor="none",
                                             edgecolor="tab:blue", linewidths=0.2,
                                             linestyles="--"))
    _equal(ax, corners.reshape(-1, 3))
    ax.set_title(f"{title} ({len(corners)} panels)")
    if filename is not None:
        fig.savefig(filename, dpi=150, bbox_inches="tight")
    return fig


def plot_cp(corners, cp, *, ax=None, filename=None, title="surface Cp", clim=None):
    """Panels coloured by Cp.

    Parameters
    ----------
    corners : ndarray (n, 4, 3) [m]
    cp : ndarray (n,) [-]
    ax : 3-D matplotlib axes, optional
    filename : str or path, optional
    title : str
    clim : (float, float), optional
        Colour limits (default: 2nd-98th percentile, so corner spikes do not
        wash out the picture).
    """
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    fig, ax = _axes3d(ax)
    lo, hi = clim if clim is not None else np.percentile(cp, [2, 98])
    norm = colors.Normalize(vmin=lo, vmax=hi if hi > lo else lo + 1e-9)
    cmap = plt.get_cmap("viridis")
    ax.add_collection3d(Poly3DCollection(list(corners), facecolors=cmap(norm(cp)),
                                         edgecolor="none"))
    _equal(ax, corners.reshape(-1, 3))
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, shrink=0.6, label="Cp")
    ax.set_title(title)
    if filename is not None:
        fig.savefig(filename, dpi=150, bbox_inches="tight")
    return fig
