"""matplotlib integration: surfaces drawn as their exact visible regions in mplot3d axes.

mplot3d sorts whole polygons by one depth each (its maintainers call it a 2.5D renderer), so
surfaces that pass through each other, or overlap cyclically, come out wrong. Here the faces
are given to sightline, which computes what the axes' camera sees exactly; the regions are
recomputed from the axes' own projection matrix each time the figure is drawn, so interactive
rotation stays right, and PDF, SVG and PNG output get the same regions.

>>> import numpy as np, matplotlib.pyplot as plt, sightline.mpl
>>> X, Y = np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9))
>>> ax = plt.figure().add_subplot(projection="3d")
>>> surfaces = sightline.mpl.add_surfaces(ax, [
...     sightline.mpl.surface(X, Y, 0.5 * X, color="tab:blue"),
...     sightline.mpl.surface(X, Y, -0.5 * X, color="tab:orange")])

The building blocks take what mplot3d's own functions take: `surface` (as `plot_surface`: X,
Y, Z grids), `trisurf` (as `plot_trisurf`: points and triangles) and `polygons` (as
`Poly3DCollection`: a list of (k, 3) vertex arrays).
"""

import numpy as np
from matplotlib import colors as mcolors
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.colors import LightSource
from matplotlib.path import Path

from . import _sightline as _sl

__all__ = ["Faces", "VisibleLines", "VisibleSurfaces", "add_surfaces", "polygons", "surface", "trisurf"]


class Faces:
    """Polygons in data coordinates with a colour each: `vertices` (n, 3), `faces` (m, k)
    vertex indices padded with -1, `rgba` (m, 4)."""

    def __init__(self, vertices, faces, rgba):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.faces = np.asarray(faces, dtype=np.int64)
        self.rgba = np.asarray(rgba, dtype=np.float64)

    def normals(self):
        """Each face's normal (Newell's method; not normalized)."""
        n = np.zeros((len(self.faces), 3))
        k = self.faces.shape[1]
        for j in range(k):
            a, b = self.faces[:, j], self.faces[:, (j + 1) % k]
            # A padded corner closes the polygon at its first vertex.
            a = np.where(a < 0, self.faces[:, 0], a)
            b = np.where(b < 0, self.faces[:, 0], b)
            p, q = self.vertices[a], self.vertices[b]
            n += np.stack(
                [
                    (p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2]),
                    (p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0]),
                    (p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1]),
                ],
                axis=1,
            )
        return n


def _colors(color, facecolors, m):
    if facecolors is not None:
        rgba = mcolors.to_rgba_array(facecolors)
        if len(rgba) == 1:
            rgba = np.repeat(rgba, m, axis=0)
        if len(rgba) != m:
            raise ValueError(f"facecolors has {len(rgba)} colours for {m} faces")
        return rgba
    return np.repeat(mcolors.to_rgba_array(color if color is not None else "C0"), m, axis=0)


def surface(X, Y, Z, *, color=None, facecolors=None):
    """A surface from X, Y, Z grids, as `Axes3D.plot_surface` takes them: one quadrilateral
    per grid cell (a cell that is not planar is split into triangles, each keeping the cell's
    id). `facecolors`: one colour per cell, (rows - 1, cols - 1, ...) or flat."""
    X, Y, Z = (np.asarray(a, dtype=np.float64) for a in np.broadcast_arrays(X, Y, Z))
    rows, cols = Z.shape
    vertices = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    i, j = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
    k = (i * cols + j).ravel()
    faces = np.column_stack([k, k + 1, k + cols + 1, k + cols])
    if facecolors is not None:
        facecolors = np.asarray(facecolors)
        if facecolors.ndim >= 2 and facecolors.shape[:2] == (rows - 1, cols - 1):
            facecolors = facecolors.reshape((rows - 1) * (cols - 1), -1)
    return Faces(vertices, faces, _colors(color, facecolors, len(faces)))


def trisurf(x, y, z, triangles=None, *, color=None, facecolors=None):
    """A surface of triangles, as `Axes3D.plot_trisurf` takes it: points x, y, z and their
    triangles (a Delaunay triangulation of x, y when not given)."""
    x, y, z = (np.asarray(a, dtype=np.float64).ravel() for a in (x, y, z))
    if triangles is None:
        from matplotlib.tri import Triangulation

        triangles = Triangulation(x, y).triangles
    faces = np.asarray(triangles, dtype=np.int64)
    return Faces(np.column_stack([x, y, z]), faces, _colors(color, facecolors, len(faces)))


def polygons(verts, *, color=None, facecolors=None):
    """Polygons as `Poly3DCollection` takes them: a list of (k, 3) vertex arrays."""
    verts = [np.asarray(v, dtype=np.float64).reshape(-1, 3) for v in verts]
    k = max(len(v) for v in verts)
    faces = np.full((len(verts), k), -1, dtype=np.int64)
    start = 0
    for f, v in enumerate(verts):
        faces[f, : len(v)] = np.arange(start, start + len(v))
        start += len(v)
    return Faces(np.vstack(verts), faces, _colors(color, facecolors, len(verts)))


def _shaded(faces, lightsource):
    """mplot3d's shading: each colour scaled by 0.3 to 1 as the face turns toward the light."""
    n = faces.normals()
    length = np.linalg.norm(n, axis=1)
    shade = np.full(len(n), np.nan)
    ok = length > 0
    shade[ok] = (n[ok] / length[ok, None]) @ lightsource.direction
    scale = np.where(np.isnan(shade), 1.0, 0.3 + 0.7 * (shade + 1) / 2)
    rgba = faces.rgba.copy()
    rgba[:, :3] *= scale[:, None]
    return rgba


def _joined(parts):
    """One `Faces` of several: vertices stacked, indices shifted, rows padded to one width."""
    k = max(p.faces.shape[1] for p in parts)
    vertices, faces, rgba, start = [], [], [], 0
    for p in parts:
        f = np.full((len(p.faces), k), -1, dtype=np.int64)
        f[:, : p.faces.shape[1]] = np.where(p.faces < 0, -1 - start, p.faces) + start
        vertices.append(p.vertices)
        faces.append(f)
        rgba.append(p.rgba)
        start += len(p.vertices)
    return Faces(np.vstack(vertices), np.vstack(faces), np.vstack(rgba))


def _ring_path(rings):
    """One path of a region's rings: the outer boundary and its holes (opposite turns, so the
    nonzero rule leaves the holes empty)."""
    verts, codes = [], []
    for ring in rings:
        verts.extend(ring)
        verts.append(ring[0])
        codes.extend([Path.MOVETO] + [Path.LINETO] * (len(ring) - 1) + [Path.CLOSEPOLY])
    return Path(np.asarray(verts), codes)


def _depth(axes, vertices):
    """The mean projected depth of some points (mplot3d orders its 3D artists by it)."""
    h = np.column_stack([vertices, np.ones(len(vertices))]) @ axes.get_proj().T
    return float(np.mean(h[:, 2] / h[:, 3]))


class VisibleSurfaces(PathCollection):
    """The exact visible regions of some faces, recomputed from the axes' projection each time
    the figure is drawn. `regions` after a draw: the `sightline.Region`s drawn, in the
    axes' projected coordinates."""

    def __init__(self, faces, *, method="auto", **kwargs):
        kwargs.setdefault("linewidths", 0.3)
        kwargs.setdefault("edgecolors", "face")
        super().__init__([], **kwargs)
        self._faces = faces
        self._scene = _sl.Scene.from_arrays(faces.vertices, faces.faces)
        self._rgba = faces.rgba
        self._method = method
        self.regions = []

    def do_3d_projection(self):
        camera = _sl.Camera.from_matplotlib(self.axes)
        self.regions = _sl.visible_set(self._scene, camera, method=self._method, coords="projected")
        self.set_paths([_ring_path(r.rings) for r in self.regions])
        colors = self._rgba[[r.face for r in self.regions]] if self.regions else np.zeros((0, 4))
        self.set_facecolor(colors)
        return _depth(self.axes, self._faces.vertices)


class VisibleLines(LineCollection):
    """The hidden-line drawing of some faces (visible strokes, and hidden ones dashed when
    asked), recomputed from the axes' projection each time the figure is drawn."""

    def __init__(self, faces, *, hidden=False, crease=30.0, **kwargs):
        kwargs.setdefault("colors", "black")
        kwargs.setdefault("linewidths", 0.8)
        super().__init__([], **kwargs)
        self._faces = faces
        self._scene = _sl.Scene.from_arrays(faces.vertices, faces.faces)
        self._hidden = hidden
        self._crease = crease
        self.strokes = []

    def do_3d_projection(self):
        camera = _sl.Camera.from_matplotlib(self.axes)
        self.strokes = _sl.lines(
            self._scene, camera, hidden=self._hidden, crease=self._crease, coords="projected"
        )
        segments = [
            np.vstack([s.points, s.points[:1]]) if s.closed else s.points for s in self.strokes
        ]
        self.set_segments(segments)
        self.set_linestyle([("solid" if s.visible else (0, (3, 2))) for s in self.strokes] or "solid")
        # In front of the surfaces.
        return _depth(self.axes, self._faces.vertices) - 1e9


def add_surfaces(ax, parts, *, shade=True, lightsource=None, lines=False, hidden=False, method="auto", **kwargs):
    """Draws `parts` (from `surface`, `trisurf`, `polygons`) in the 3D axes `ax` as one scene,
    so that where they pass through or in front of each other is exact. `shade`: scale colours
    by the faces' angle to `lightsource` as mplot3d does; `lines`: also draw the line drawing
    (silhouettes, boundaries, intersections, creases), its hidden lines dashed with `hidden`.
    Other keywords go to the `VisibleSurfaces` collection. Returns it (and the `VisibleLines`
    when `lines`). Fits the axes' limits to the parts."""
    faces = _joined(list(parts))
    if shade:
        faces = Faces(faces.vertices, faces.faces, _shaded(faces, lightsource or LightSource(azdeg=225, altdeg=19.4712)))
    had_data = ax.has_data()
    collection = VisibleSurfaces(faces, method=method, **kwargs)
    ax.add_collection(collection)
    lo, hi = faces.vertices.min(axis=0), faces.vertices.max(axis=0)
    ax.auto_scale_xyz([lo[0], hi[0]], [lo[1], hi[1]], [lo[2], hi[2]], had_data=had_data)
    if not lines:
        return collection
    drawn = VisibleLines(faces, hidden=hidden)
    ax.add_collection(drawn)
    return collection, drawn
