"""The Python API against the `sightline` command on the same scenes and cameras, arrays
against files, and errors on bad input."""

import json
import pathlib

import numpy as np
import pytest

import sightline
from conftest import FIXTURES

SIZE = (160, 120)
VIEWS = ["iso", "front"]
SCENES = sorted(p.name for p in FIXTURES.glob("*.obj"))


def regions_by_face(regions):
    """{face: [rings as lists of [x, y]]} in drawing order, as the command's JSON has them."""
    out = {}
    for r in regions:
        out.setdefault(r.face, []).append([ring.tolist() for ring in r.rings])
    return out


def json_regions(doc):
    """The command's JSON regions per face; a region there is its rings, even-odd."""
    return {f["id"]: f["regions"] for f in doc["faces"]}


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("view", VIEWS)
def test_visible_set_is_the_commands_json(cli, name, view):
    scene = sightline.Scene.from_file(FIXTURES / name)
    camera = sightline.Camera(view=view, size=SIZE)
    doc = json.loads(
        cli("render", FIXTURES / name, "--view", view, "--size", "%dx%d" % SIZE, "--to", "json", "-o", "-")
    )
    ours = regions_by_face(sightline.visible_set(scene, camera))
    theirs = json_regions(doc)
    assert set(ours) == set(theirs)
    for face, regions in theirs.items():
        # A JSON region may hold an island inside a hole: the API gives it as its own region.
        flat = sorted(ring for region in regions for ring in region)
        assert sorted(ring for region in ours[face] for ring in region) == flat


@pytest.mark.parametrize("method", sightline.method_names(exact=True))
def test_every_exact_method_gives_the_same_regions(method):
    scene = sightline.Scene.from_file(FIXTURES / "interpenetrating.obj")
    camera = sightline.Camera(view="iso", size=SIZE)
    auto = regions_by_face(sightline.visible_set(scene, camera))
    assert regions_by_face(sightline.visible_set(scene, camera, method=method)) == auto


def test_regions_have_their_outer_ring_first_and_holes_after():
    # A square with a square hole: one region, outer ring then one hole.
    outer = [(0, 0), (4, 0), (4, 4), (0, 4)]
    inner = [(1, 1), (3, 1), (3, 3), (1, 3)]
    v = np.array([(x, y, 0.0) for x, y in outer + inner])
    faces = np.array([[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
    scene = sightline.Scene.from_arrays(v, faces)
    camera = sightline.Camera(eye=(2, 2, 10), target=(2, 2, 0), up=(0, 1, 0), ortho=5, size=(100, 100))
    regions = sightline.visible_set(scene, camera)
    assert sorted(r.face for r in regions) == [0, 1, 2, 3]
    for r in regions:
        assert r.outer.shape[1] == 2 and r.outer.dtype == np.float64
        assert r.holes == []
    # The four trapezoids cover 16 - 4 = 12 square units of 5x5 units in 100x100 pixels.
    assert sum(r.area for r in regions) == pytest.approx(12 * 400, rel=1e-9)


def obj_text(vertices, faces):
    lines = ["v %r %r %r" % tuple(map(float, v)) for v in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f if i >= 0) for f in faces]
    return "\n".join(lines) + "\n"


def two_crossing_planes():
    """matplotlib issue 29060's case: two planes passing through each other."""
    s = np.linspace(-1, 1, 5)
    x, y = np.meshgrid(s, s)
    grid = np.stack([x.ravel(), y.ravel()], axis=1)
    a = np.column_stack([grid, 0.5 * grid[:, 0]])
    b = np.column_stack([grid, -0.5 * grid[:, 0] + 0.2])
    vertices = np.vstack([a, b])
    quads = []
    for j in range(4):
        for i in range(4):
            k = 5 * j + i
            quads.append([k, k + 1, k + 6, k + 5])
    quads = np.array(quads)
    faces = np.vstack([quads, quads + 25])
    return vertices, faces


def test_arrays_give_the_same_regions_as_the_same_scene_from_a_file(tmp_path):
    vertices, faces = two_crossing_planes()
    path = tmp_path / "planes.obj"
    path.write_text(obj_text(vertices, faces))
    camera = sightline.Camera(eye=(3, -4, 2), target=(0, 0, 0), up=(0, 0, 1), fov=35, size=SIZE)
    from_file = sightline.visible_set(sightline.Scene.from_file(path), camera)
    from_arrays = sightline.visible_set(sightline.Scene.from_arrays(vertices, faces), camera)
    assert regions_by_face(from_arrays) == regions_by_face(from_file)
    # Both planes show: each hides part of the other along their exact meeting line.
    shown = {r.face for r in from_arrays}
    assert shown & set(range(16)) and shown & set(range(16, 32))


def test_arrays_of_other_dtypes_and_padded_rows_are_accepted():
    vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]]
    faces = np.array([[0, 1, 2, 3], [1, 4, 2, -1]], dtype=np.int32)
    scene = sightline.Scene.from_arrays(vertices, faces, colors=[1.0, 0.0, 0.0], transparency=0.0)
    assert scene.face_count == 2
    camera = sightline.Camera(eye=(1, 0.5, 5), target=(1, 0.5, 0), up=(0, 1, 0), fov=30, size=(64, 64))
    regions = sightline.visible_set(scene, camera)
    assert sorted(r.face for r in regions) == [0, 1]
    assert all(r.color[1] == 0.0 and r.color[2] == 0.0 and r.color[0] > 0 for r in regions)


# The z-buffer's PNG draws the cube's and the glass's translucent faces opaque, and says so.
@pytest.mark.filterwarnings("ignore:.*translucent faces as opaque")
@pytest.mark.parametrize("name", ["cube.obj", "interpenetrating.obj", "tinted_glass.obj"])
def test_svg_and_png_are_the_commands_bytes(cli, name):
    scene = sightline.Scene.from_file(FIXTURES / name)
    camera = sightline.Camera(view="iso", size=SIZE)
    size = "%dx%d" % SIZE
    svg = cli("render", FIXTURES / name, "--view", "iso", "--size", size, "--to", "svg", "-o", "-")
    assert sightline.to_svg(scene, camera).encode() == svg
    png = cli("render", FIXTURES / name, "--view", "iso", "--size", size, "--to", "png", "-o", "/dev/stdout")
    assert sightline.to_png(scene, camera) == png


@pytest.mark.parametrize("name", ["cube.obj", "interpenetrating.obj", "cyclic_bars.obj"])
def test_lines_are_the_commands_strokes(cli, name):
    scene = sightline.Scene.from_file(FIXTURES / name)
    camera = sightline.Camera(view="iso", size=SIZE)
    doc = json.loads(
        cli("lines", FIXTURES / name, "--view", "iso", "--size", "%dx%d" % SIZE, "--to", "json", "-o", "-")
    )
    strokes = sightline.lines(scene, camera)
    assert len(strokes) == len(doc["strokes"])
    for ours, theirs in zip(strokes, doc["strokes"]):
        assert ours.kind == theirs["kind"]
        assert ours.visible == (theirs["visibility"] == "visible")
        assert (ours.qi, ours.closed) == (theirs["qi"], theirs["closed"])
        assert ours.points.tolist() == theirs["points"]
    visible_only = sightline.lines(scene, camera, hidden=False)
    assert all(s.visible for s in visible_only)


@pytest.mark.parametrize("bad", sorted(p.name for p in (FIXTURES / "bad").iterdir()))
def test_bad_files_raise_with_their_file(bad):
    with pytest.raises(sightline.SightlineError) as e:
        sightline.Scene.from_file(FIXTURES / "bad" / bad)
    # The file at fault: the one loaded, or the material library it names (same stem here).
    assert str(FIXTURES / "bad" / pathlib.Path(bad).stem) in str(e.value)


@pytest.mark.parametrize(
    "vertices, faces, kwargs, message",
    [
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], {}, "faces[0]: vertex index 3 out of range"),
        ([[0, 0, 0], [1, 0, float("nan")], [0, 1, 0]], [[0, 1, 2]], {}, "vertices[1] is not finite"),
        ([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], {}, "vertices must be (n, 3)"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, -1, 2]], {}, "faces[0]: -1 only pads the end"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"colors": [2, 0, 0]}, "colors[0] is not within"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"transparency": [0.5, 0.5]}, "transparency must be"),
        ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]], {}, "no face with an area"),
    ],
)
def test_bad_arrays_raise_naming_the_element(vertices, faces, kwargs, message):
    with pytest.raises(sightline.SightlineError) as e:
        sightline.Scene.from_arrays(np.array(vertices, float), np.array(faces), **kwargs)
    assert message in str(e.value)


def test_bad_options_raise():
    scene = sightline.Scene.from_file(FIXTURES / "cube.obj")
    with pytest.raises(sightline.SightlineError, match="fov"):
        sightline.Camera(eye=(0, 0, 5), target=(0, 0, 0), fov=-40)
    with pytest.raises(sightline.SightlineError, match="view must be"):
        sightline.Camera(view="sideways")
    with pytest.raises(sightline.SightlineError, match="no exact visible regions"):
        sightline.visible_set(scene, sightline.Camera(view="iso"), method="zbuffer")
    with pytest.raises(sightline.SightlineError, match="not both"):
        sightline.Camera(eye=(0, 0, 5), target=(0, 0, 0), fov=30, ortho=2)
    with pytest.raises(sightline.SightlineError):
        sightline.Scene.from_file(FIXTURES / "no_such_file.obj")


def test_the_commands_warnings_are_python_warnings():
    glass = sightline.Scene.from_file(FIXTURES / "tinted_glass.obj")
    with pytest.warns(UserWarning, match="translucent faces as opaque"):
        sightline.to_png(glass, sightline.Camera(view="iso", size=SIZE), method="zbuffer")
    cube = sightline.Scene.from_file(FIXTURES / "cube.obj")
    away = sightline.Camera(eye=(0.5, 0.5, 5), target=(0.5, 0.5, 10), up=(0, 1, 0), fov=30, size=SIZE)
    with pytest.warns(UserWarning, match="sees none of the 6 faces"):
        sightline.to_svg(cube, away)


def test_an_alpha_column_is_the_faces_opacity():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [0, 1, 1]], float)
    faces = [[0, 1, 2], [3, 4, 5]]
    camera = sightline.Camera(eye=(0.3, 0.3, 5), target=(0.3, 0.3, 0), up=(0, 1, 0), fov=30, size=(64, 64))
    # The nearer face (z = 1) is the translucent one.
    rgba = sightline.Scene.from_arrays(v, faces, colors=[[1, 0, 0, 1], [0, 0, 1, 0.25]])
    split = sightline.Scene.from_arrays(v, faces, colors=[[1, 0, 0], [0, 0, 1]], transparency=[0, 0.75])
    assert sightline.to_svg(rgba, camera) == sightline.to_svg(split, camera)
    opacity = {r.face: r.opacity for r in sightline.visible_set(rgba, camera)}
    assert opacity == {0: 1.0, 1: 0.25}
    with pytest.raises(sightline.SightlineError, match="not both"):
        sightline.Scene.from_arrays(v, faces, colors=[1, 0, 0, 0.5], transparency=0.5)
    with pytest.raises(sightline.SightlineError, match=r"colors\[0\]: alpha 2"):
        sightline.Scene.from_arrays(v, faces, colors=[1, 0, 0, 2])


def test_messages_name_keywords_not_the_commands_flags():
    with pytest.raises(sightline.SightlineError) as e:
        sightline.Camera(eye=(0, 0, 5), target=(0, 0, 0), fov=-40)
    assert str(e.value).startswith("fov=") and "--" not in str(e.value)
    glass = sightline.Scene.from_file(FIXTURES / "tinted_glass.obj")
    with pytest.warns(UserWarning) as caught:
        sightline.to_png(glass, sightline.Camera(view="iso", size=SIZE), method="zbuffer")
    assert all("--" not in str(w.message) for w in caught)
    assert any("method=zbuffer draws translucent faces" in str(w.message) for w in caught)
