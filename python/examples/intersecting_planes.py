"""Two planes passing through each other (matplotlib issue 29060): mplot3d's own result next
to sightline's, written to the file given (default intersecting_planes.png).

    python python/examples/intersecting_planes.py docs/python_planes.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sightline.mpl  # noqa: E402


def planes():
    """The two surfaces: z = x/2 and z = -x/2 over [-1, 1]^2, as plot_surface grids."""
    X, Y = np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9))
    return (X, Y, 0.5 * X, "tab:blue"), (X, Y, -0.5 * X, "tab:orange")


def figure():
    """The figure: mplot3d on the left, sightline on the right, same view. Returns the figure
    and sightline's collection (its `regions` are filled in when the figure is drawn)."""
    fig = plt.figure(figsize=(9, 4), dpi=100)
    left = fig.add_subplot(1, 2, 1, projection="3d")
    for X, Y, Z, color in planes():
        left.plot_surface(X, Y, Z, color=color)
    left.set_title("mplot3d: one plane over the other")
    right = fig.add_subplot(1, 2, 2, projection="3d")
    parts = [sightline.mpl.surface(X, Y, Z, color=color) for X, Y, Z, color in planes()]
    collection, _ = sightline.mpl.add_surfaces(right, parts, lines=True)
    right.set_title("sightline: they meet at x = 0")
    for ax in (left, right):
        ax.view_init(elev=30, azim=-60)
        ax.set_zlim(-0.6, 0.6)
    return fig, collection


if __name__ == "__main__":
    fig, _ = figure()
    fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "intersecting_planes.png")
