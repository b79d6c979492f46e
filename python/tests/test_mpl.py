"""The matplotlib integration: the camera read off an Axes3D, the example's regions against
the command's on the same projected scene, and regions recomputed when the view turns."""

import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from mpl_toolkits.mplot3d import proj3d  # noqa: E402

import sightline  # noqa: E402
import sightline.mpl  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))
import intersecting_planes  # noqa: E402


def test_a_matplotlib_camera_projects_as_mplot3d_does():
    fig = plt.figure(figsize=(4, 3), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.set_xlim(-0.2, 1.2), ax.set_ylim(-0.2, 1.2), ax.set_zlim(0, 1)
    ax.view_init(elev=25, azim=-60)
    fig.canvas.draw()
    v = np.array([[0, 0, 0], [1, 0, 0.2], [0, 1, 0.5]], float)
    camera = sightline.Camera.from_matplotlib(ax)
    assert camera.size == (round(ax.bbox.width), round(ax.bbox.height))
    (region,) = sightline.visible_set(sightline.Scene.from_arrays(v, [[0, 1, 2]]), camera, coords="projected")
    tx, ty, _ = proj3d.proj_transform(v[:, 0], v[:, 1], v[:, 2], ax.get_proj())
    theirs = sorted(zip(tx, ty))
    ours = sorted(map(tuple, region.outer))
    assert np.allclose(ours, theirs, rtol=0, atol=1e-12)
    plt.close(fig)


def projected(matrix, vertices):
    """Vertices through a projection camera as the engine maps them: each coordinate summed
    in the same order, depth negated."""
    m = matrix
    out = []
    for x, y, z in vertices:
        h = [m[i][0] * x + m[i][1] * y + m[i][2] * z + m[i][3] for i in range(4)]
        out.append((h[0] / h[3], h[1] / h[3], -h[2] / h[3]))
    return np.array(out)


def test_the_examples_regions_are_the_commands_on_the_projected_scene(cli, tmp_path):
    fig, collection = intersecting_planes.figure()
    fig.canvas.draw()
    ax = collection.axes
    drawn = collection.regions
    assert drawn, "the figure draws regions"
    # Both planes show, each cut exactly where the other passes in front of it.
    faces = {r.face for r in drawn}
    assert min(faces) < 64 <= max(faces)
    # The same scene projected and framed as the engine does, through the command.
    camera = sightline.Camera.from_matplotlib(ax)
    v = collection._faces.vertices
    p = projected(ax.get_proj(), v)
    lo, hi = p.min(axis=0), p.max(axis=0)
    w, h = camera.size
    lo, hi = lo.tolist(), hi.tolist()
    height = 1.02 * max(hi[1] - lo[1], (hi[0] - lo[0]) / (w / h))
    c = [0.5 * (a + b) for a, b in zip(lo, hi)]
    depth = max(hi[2] - lo[2], height)
    obj = tmp_path / "projected.obj"
    lines = ["v %r %r %r" % tuple(map(float, q)) for q in p]
    lines += ["f " + " ".join(str(i + 1) for i in f if i >= 0) for f in collection._faces.faces]
    obj.write_text("\n".join(lines) + "\n")
    vec = lambda *x: ",".join(repr(float(t)) for t in x)  # noqa: E731
    doc = json.loads(
        cli(
            "render", obj, "--eye", vec(c[0], c[1], hi[2] + depth), "--target", vec(c[0], c[1], lo[2]),
            "--up", "0,1,0", "--ortho", repr(float(height)), "--size", "%dx%d" % (w, h),
            "--to", "json", "-o", "-",
        )
    )
    unit = height / h

    def to_projected(ring):
        return [[c[0] + (x - 0.5 * w) * unit, c[1] - (y - 0.5 * h) * unit] for x, y in ring]

    theirs = sorted(
        (f["id"], sorted(map(str, (to_projected(r) for r in region))))
        for f in doc["faces"]
        for region in f["regions"]
    )
    ours = sorted((r.face, sorted(map(str, (ring.tolist() for ring in r.rings)))) for r in drawn)
    assert ours == theirs
    plt.close(fig)


def test_regions_follow_the_view_when_it_turns():
    fig, collection = intersecting_planes.figure()
    fig.canvas.draw()
    before = {r.face for r in collection.regions}, sum(r.area for r in collection.regions)
    collection.axes.view_init(elev=-40, azim=120)
    fig.canvas.draw()
    after = {r.face for r in collection.regions}, sum(r.area for r in collection.regions)
    assert after != before
    plt.close(fig)


def test_building_blocks_take_what_mplot3d_takes():
    X, Y = np.meshgrid(np.linspace(0, 1, 4), np.linspace(0, 1, 3))
    s = sightline.mpl.surface(X, Y, X * Y, facecolors=np.full((2, 3, 4), 0.5))
    assert s.faces.shape == (6, 4) and s.rgba.shape == (6, 4)
    t = sightline.mpl.trisurf([0, 1, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1])
    assert t.faces.shape[1] == 3 and len(t.faces) == 2
    p = sightline.mpl.polygons([[(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]])
    assert p.faces.tolist() == [[0, 1, 2, -1], [3, 4, 5, 6]]
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    collection = sightline.mpl.add_surfaces(ax, [s, t, p], shade=False)
    fig.canvas.draw()
    assert {r.face for r in collection.regions} <= set(range(6 + 2 + 2))
    plt.close(fig)


def test_a_projection_camera_refuses_points_behind_it():
    behind = np.diag([1.0, 1.0, 1.0, -1.0])
    camera = sightline.Camera.from_matrix(behind, size=(10, 10))
    scene = sightline.Scene.from_arrays([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(sightline.SightlineError, match="not in front of the projection"):
        sightline.visible_set(scene, camera)
    with pytest.raises(sightline.SightlineError, match="needs a projection camera"):
        sightline.visible_set(scene, sightline.Camera(view="iso"), coords="projected")
