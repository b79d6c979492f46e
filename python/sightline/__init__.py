"""sightline: exact visible regions and hidden-line drawings of 3D scenes.

Which parts of a scene a camera sees, computed exactly in object space: each visible region
knows its source face, and two faces passing through each other meet exactly along their
intersection, whatever their sizes (a painter's sort, as in matplotlib's mplot3d, orders whole
polygons by one depth each and cannot).

>>> import numpy as np, sightline
>>> scene = sightline.Scene.from_arrays(
...     np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), np.array([[0, 1, 2]]))
>>> camera = sightline.Camera(eye=(0, 0, 5), target=(0, 0, 0), up=(0, 1, 0), fov=30, size=(64, 64))
>>> [r.face for r in sightline.visible_set(scene, camera)]
[0]

Coordinates of regions and strokes are pixels of the camera's image, y down.
"""

from ._sightline import (
    Camera,
    Region,
    Scene,
    SightlineError,
    Stroke,
    lines,
    method_names,
    to_png,
    to_svg,
    visible_set,
)

__all__ = [
    "Camera",
    "Region",
    "Scene",
    "SightlineError",
    "Stroke",
    "lines",
    "method_names",
    "to_png",
    "to_svg",
    "visible_set",
]
