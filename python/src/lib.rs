//! The compiled half of the `sightline` Python package (`sightline._sightline`): scenes,
//! cameras, exact visible regions, hidden lines and pictures, numpy in and out. The Python half
//! (`python/sightline/`) re-exports these and adds the matplotlib integration.
//!
//! Every call releases the GIL while the engine works, and every engine error becomes a
//! `SightlineError` whose message is the engine's (it names the file and line, or the array
//! element).

use glam::DVec3;
use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use sightline::camera::{CameraSpec, NamedView};
use sightline::draw::{self, DrawOptions};
use sightline::lines::{LineOptions, line_drawing};
use sightline::methods::{self, Engine, Output};
use sightline::output::canonical::regions_of_rings;
use sightline::output::drawing::DrawItem;
use sightline::paint::Fill;
use sightline::pipeline;
use sightline::project::CullMode;
use sightline::render::{self, RenderOptions};
use sightline::scene::{Material, SceneBuilder};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

create_exception!(
    _sightline,
    SightlineError,
    PyValueError,
    "Bad input or options: the message names the file and line, or the array element."
);

fn err(e: impl std::fmt::Display) -> PyErr {
    SightlineError::new_err(keywords(&e.to_string()))
}

/// The engine's messages name the command's flags; Python users pass keywords.
fn keywords(message: &str) -> String {
    let mut m = message.to_string();
    for flag in [
        "method", "fov", "ortho", "near", "far", "size", "eye", "target", "up",
    ] {
        m = m.replace(&format!("--{flag} "), &format!("{flag}="));
    }
    m
}

/// `x` as a C-contiguous numpy array of `dtype`: the same array when it already is one.
fn contiguous<'py>(x: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    x.py()
        .import("numpy")?
        .call_method1("ascontiguousarray", (x, dtype))
}

/// An image size of at least one pixel each way.
fn check_size(size: (u32, u32)) -> PyResult<()> {
    if size.0 == 0 || size.1 == 0 {
        return Err(err(format!("size must be positive, got {size:?}")));
    }
    Ok(())
}

/// A scene: faces with provenance (face ids are the input order: file order, or rows of the
/// faces array), materials and lights.
#[pyclass(frozen, module = "sightline")]
struct Scene {
    inner: Arc<sightline::Scene>,
}

#[pymethods]
impl Scene {
    /// Loads OBJ (+MTL), STL, PLY or X3D, optionally gzipped.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
        let scene = py.detach(|| sightline::load(&path, None)).map_err(err)?;
        Ok(Scene {
            inner: Arc::new(scene),
        })
    }

    /// A scene from `vertices` (n, 3) and `faces` (m, k) vertex indices (a row may end early
    /// with -1 padding, for polygons of mixed sizes); `colors`: one RGB or RGBA in [0, 1] for
    /// every face, (3,) or (4,), or per face, (m, 3) or (m, 4), alpha being the opacity;
    /// `transparency`: 0 (opaque) to 1, one value or per face (m,). Face ids are row numbers; a degenerate face is dropped and its id left unused.
    #[staticmethod]
    #[pyo3(signature = (vertices, faces, colors = None, transparency = None))]
    fn from_arrays<'py>(
        py: Python<'py>,
        vertices: &Bound<'py, PyAny>,
        faces: &Bound<'py, PyAny>,
        colors: Option<&Bound<'py, PyAny>>,
        transparency: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Scene> {
        let vertices = contiguous(vertices, "float64")?;
        let vertices: PyReadonlyArray2<f64> = vertices
            .extract()
            .map_err(|_| err("vertices must be an (n, 3) array of numbers"))?;
        let faces = contiguous(faces, "int64")?;
        let faces: PyReadonlyArray2<i64> = faces
            .extract()
            .map_err(|_| err("faces must be an (m, k) array of vertex indices"))?;
        if vertices.shape()[1] != 3 {
            return Err(err(format!(
                "vertices must be (n, 3), got {:?}",
                vertices.shape()
            )));
        }
        let m = faces.shape()[0];
        // RGB or RGBA rows; an alpha column is an opacity (transparency = 1 - alpha).
        let rgba: Option<Vec<[f64; 4]>> = match colors {
            None => None,
            Some(c) => {
                let c = contiguous(c, "float64")?;
                let row = |r: &[f64]| [r[0], r[1], r[2], r.get(3).copied().unwrap_or(1.0)];
                let rows: Vec<[f64; 4]> = match c.extract::<PyReadonlyArray1<f64>>() {
                    Ok(one) if one.len() == 3 || one.len() == 4 => vec![row(one.as_slice()?); m],
                    _ => {
                        let per: PyReadonlyArray2<f64> = c
                            .extract()
                            .map_err(|_| err("colors must be (3,), (4,), (m, 3) or (m, 4)"))?;
                        let shape = per.shape();
                        if shape[0] != m || !(shape[1] == 3 || shape[1] == 4) {
                            return Err(err(format!(
                                "colors must be (3,), (4,), ({m}, 3) or ({m}, 4), got {shape:?}"
                            )));
                        }
                        per.as_array()
                            .rows()
                            .into_iter()
                            .map(|r| row(&r.to_vec()))
                            .collect()
                    }
                };
                Some(rows)
            }
        };
        if let Some((k, c)) = rgba
            .iter()
            .flatten()
            .enumerate()
            .find(|(_, c)| !(0.0..=1.0).contains(&c[3]))
        {
            return Err(err(format!(
                "colors[{k}]: alpha {} is not within [0, 1]",
                c[3]
            )));
        }
        let has_alpha = rgba.as_ref().is_some_and(|c| c.iter().any(|c| c[3] != 1.0));
        let colors: Option<Vec<[f64; 3]>> = rgba
            .as_ref()
            .map(|c| c.iter().map(|c| [c[0], c[1], c[2]]).collect());
        if has_alpha && transparency.is_some() {
            return Err(err(
                "give opacity as the colours' alpha or as transparency, not both",
            ));
        }
        let transparency: Option<Vec<f64>> = match transparency {
            None if has_alpha => rgba
                .as_ref()
                .map(|c| c.iter().map(|c| 1.0 - c[3]).collect()),
            None => None,
            Some(t) => {
                if let Ok(one) = t.extract::<f64>() {
                    Some(vec![one; m])
                } else {
                    let t = contiguous(t, "float64")?;
                    let per: PyReadonlyArray1<f64> = t
                        .extract()
                        .map_err(|_| err("transparency must be a number or (m,)"))?;
                    if per.len() != m {
                        return Err(err(format!(
                            "transparency must be a number or ({m},), got ({},)",
                            per.len()
                        )));
                    }
                    Some(per.as_slice()?.to_vec())
                }
            }
        };
        let vertices = vertices.as_array();
        let faces = faces.as_array();
        let scene = py.detach(|| {
            scene_of_arrays(vertices, faces, colors.as_deref(), transparency.as_deref())
        })?;
        Ok(Scene {
            inner: Arc::new(scene),
        })
    }

    /// Number of faces (after dropping degenerate ones; ids keep the input numbering).
    #[getter]
    fn face_count(&self) -> usize {
        self.inner.faces.len()
    }

    /// The smallest box holding every vertex: ((x0, y0, z0), (x1, y1, z1)).
    #[getter]
    fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        self.inner
            .bounds()
            .map(|(lo, hi)| (lo.to_array(), hi.to_array()))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, {} faces, {} vertices)",
            self.inner.source,
            self.inner.faces.len(),
            self.inner.positions.len()
        )
    }
}

/// The scene of the arrays (checked element by element).
fn scene_of_arrays(
    vertices: numpy::ndarray::ArrayView2<'_, f64>,
    faces: numpy::ndarray::ArrayView2<'_, i64>,
    colors: Option<&[[f64; 3]]>,
    transparency: Option<&[f64]>,
) -> PyResult<sightline::Scene> {
    let mut b = SceneBuilder::new("arrays");
    b.begin_mesh("arrays");
    for (i, v) in vertices.rows().into_iter().enumerate() {
        let p = DVec3::new(v[0], v[1], v[2]);
        if !p.is_finite() {
            return Err(err(format!(
                "vertices[{i}] is not finite: {:?}",
                p.to_array()
            )));
        }
        b.add_vertex(p);
    }
    let n = vertices.shape()[0] as i64;
    let mut materials: HashMap<([u64; 3], u64), u32> = HashMap::new();
    let mut corners = Vec::new();
    for (k, row) in faces.rows().into_iter().enumerate() {
        corners.clear();
        for (j, &v) in row.iter().enumerate() {
            if v < 0 {
                if row.iter().skip(j).any(|&w| w >= 0) {
                    return Err(err(format!(
                        "faces[{k}]: -1 only pads the end of a row (index {v} at column {j})"
                    )));
                }
                break;
            }
            if v >= n {
                return Err(err(format!(
                    "faces[{k}]: vertex index {v} out of range ({n} vertices)"
                )));
            }
            corners.push(v as u32);
        }
        let color = colors.map(|c| c[k]);
        let alpha = transparency.map(|t| t[k]);
        if let Some(c) = color
            && c.iter().any(|x| !(0.0..=1.0).contains(x))
        {
            return Err(err(format!("colors[{k}] is not within [0, 1]: {c:?}")));
        }
        if let Some(t) = alpha
            && !(0.0..=1.0).contains(&t)
        {
            return Err(err(format!("transparency[{k}] is not within [0, 1]: {t}")));
        }
        let material = match (color, alpha) {
            (None, None) => b.default_material(),
            (c, t) => {
                let base = Material::default();
                let c = c.unwrap_or(base.diffuse);
                let t = t.unwrap_or(0.0);
                *materials
                    .entry((c.map(f64::to_bits), t.to_bits()))
                    .or_insert_with(|| {
                        b.add_material(Material {
                            name: format!("face {k}"),
                            diffuse: c,
                            transparency: t,
                            ..base
                        })
                    })
            }
        };
        b.add_face(&corners, material);
    }
    b.finish()
        .ok_or_else(|| err("the arrays hold no face with an area"))
}

/// A camera: where it looks from and to, its lens and its image size. Parts not given are
/// fitted to each scene it is used with (a named `view`, the near and far planes).
#[pyclass(frozen, module = "sightline")]
#[derive(Clone)]
struct Camera {
    spec: CameraSpec,
    /// A projection matrix (`Camera.from_matrix`, `Camera.from_matplotlib`): scene points map
    /// to `M @ [x, y, z, 1]`, then divided by w.
    projection: Option<[[f64; 4]; 4]>,
}

/// Where the image of a projection camera lies in its projected coordinates: pixel (px, py) is
/// the point (cx + (px - w/2)·unit, cy - (py - h/2)·unit).
#[derive(Clone, Copy, Debug)]
struct Frame {
    centre: [f64; 2],
    unit: f64,
    size: (u32, u32),
}

impl Frame {
    fn point(&self, [px, py]: [f64; 2]) -> [f64; 2] {
        let (w, h) = (self.size.0 as f64, self.size.1 as f64);
        [
            self.centre[0] + (px - 0.5 * w) * self.unit,
            self.centre[1] - (py - 0.5 * h) * self.unit,
        ]
    }
}

/// A scene and the engine's camera for it, with the frame of a projection camera.
struct Placed {
    scene: Arc<sightline::Scene>,
    camera: sightline::Camera,
    frame: Option<Frame>,
}

impl Camera {
    /// The engine's camera for `scene`. A projection camera maps the scene's vertices through
    /// its matrix (each coordinate rounded once in f64: the input rounding of this path) with
    /// depth negated, and looks at them orthographically down the depth axis, framing their box.
    fn place(&self, scene: &Arc<sightline::Scene>) -> Result<Placed, String> {
        let Some(m) = self.projection else {
            let camera = self.spec.resolve_for(scene).map_err(|e| e.to_string())?;
            return Ok(Placed {
                scene: scene.clone(),
                camera,
                frame: None,
            });
        };
        let mut projected = (**scene).clone();
        for (i, p) in projected.positions.iter_mut().enumerate() {
            let h: Vec<f64> = m
                .iter()
                .map(|r| r[0] * p.x + r[1] * p.y + r[2] * p.z + r[3])
                .collect();
            let q = DVec3::new(h[0] / h[3], h[1] / h[3], -h[2] / h[3]);
            if h[3].is_nan() || h[3] <= 0.0 || !q.is_finite() {
                return Err(format!(
                    "vertex {i} {:?} is not in front of the projection (w = {})",
                    p.to_array(),
                    h[3]
                ));
            }
            *p = q;
        }
        // Corner normals were of the unprojected scene.
        projected.corner_normals.clear();
        let (lo, hi) = projected
            .bounds()
            .ok_or_else(|| "the scene has no vertex".to_string())?;
        let size = self.spec.size.unwrap_or(sightline::camera::DEFAULT_SIZE);
        let aspect = size.0 as f64 / size.1 as f64;
        let extent = hi - lo;
        // A little margin, so that no region touches the image's edge.
        let height = 1.02 * extent.y.max(extent.x / aspect);
        if !(height > 0.0 && height.is_finite()) {
            return Err("the projected scene has no extent on screen".into());
        }
        let centre = 0.5 * (lo + hi);
        let depth = extent.z.max(height);
        let spec = CameraSpec {
            eye: Some(DVec3::new(centre.x, centre.y, hi.z + depth)),
            target: Some(DVec3::new(centre.x, centre.y, lo.z)),
            up: Some(DVec3::Y),
            ortho_height: Some(height),
            size: Some(size),
            ..CameraSpec::default()
        };
        let projected = Arc::new(projected);
        let camera = spec.resolve_for(&projected).map_err(|e| e.to_string())?;
        Ok(Placed {
            scene: projected,
            camera,
            frame: Some(Frame {
                centre: [centre.x, centre.y],
                unit: height / size.1 as f64,
                size,
            }),
        })
    }
}

fn vec3(v: Option<[f64; 3]>) -> Option<DVec3> {
    v.map(DVec3::from_array)
}

#[pymethods]
impl Camera {
    /// `eye`, `target`, `up`: 3-vectors; `fov`: vertical field of view in degrees
    /// (perspective), or `ortho`: the view's height in scene units (orthographic); `size`:
    /// (width, height) in pixels; `near`, `far`: clipping distances; `view`: one of "front",
    /// "back", "top", "bottom", "left", "right", "iso", fitted to the scene (eye and target
    /// then optional).
    #[new]
    #[pyo3(signature = (eye = None, target = None, up = None, fov = None, ortho = None, size = (1024, 1024), near = None, far = None, view = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        eye: Option<[f64; 3]>,
        target: Option<[f64; 3]>,
        up: Option<[f64; 3]>,
        fov: Option<f64>,
        ortho: Option<f64>,
        size: (u32, u32),
        near: Option<f64>,
        far: Option<f64>,
        view: Option<&str>,
    ) -> PyResult<Camera> {
        let view = view.map(named_view).transpose()?;
        if fov.is_some() && ortho.is_some() {
            return Err(err(
                "give fov (perspective) or ortho (orthographic), not both",
            ));
        }
        check_size(size)?;
        let spec = CameraSpec {
            view: view.or((eye.is_none()).then_some(NamedView::Iso)),
            eye: vec3(eye),
            target: vec3(target),
            up: vec3(up),
            fovy_deg: fov,
            ortho_height: ortho,
            near,
            far,
            size: Some(size),
            ..CameraSpec::default()
        };
        spec.check(None).map_err(err)?;
        Ok(Camera {
            spec,
            projection: None,
        })
    }

    /// A camera from a 4x4 projection matrix `M` (a scene point p maps to `M @ [p, 1]`, then
    /// divided by w, which must be positive: in front), as graphics APIs and matplotlib build
    /// them; x right, y up and depth growing away from the viewer in the projected coordinates.
    /// `size`: the image in pixels. With this camera, `coords="projected"` gives regions and
    /// strokes in the projected x and y.
    #[staticmethod]
    #[pyo3(signature = (matrix, size = (1024, 1024)))]
    fn from_matrix(matrix: &Bound<'_, PyAny>, size: (u32, u32)) -> PyResult<Camera> {
        let m = contiguous(matrix, "float64")?;
        let m: PyReadonlyArray2<f64> = m
            .extract()
            .map_err(|_| err("matrix must be a 4x4 array of numbers"))?;
        if m.shape() != [4, 4] {
            return Err(err(format!("matrix must be 4x4, got {:?}", m.shape())));
        }
        let m = m.as_array();
        let rows: [[f64; 4]; 4] = std::array::from_fn(|i| std::array::from_fn(|j| m[[i, j]]));
        if rows.iter().flatten().any(|v| !v.is_finite()) {
            return Err(err("matrix has a value that is not finite"));
        }
        check_size(size)?;
        Ok(Camera {
            spec: CameraSpec {
                size: Some(size),
                ..CameraSpec::default()
            },
            projection: Some(rows),
        })
    }

    /// The camera of a matplotlib 3D axes as it is now: its own projection matrix
    /// (`ax.get_proj()`, data coordinates to its projected ones, the same matrix mplot3d draws
    /// with) and, unless given, the axes' size in pixels. Regions and strokes with
    /// `coords="projected"` are in the coordinates mplot3d draws its 2D paths in.
    #[staticmethod]
    #[pyo3(signature = (ax, size = None))]
    fn from_matplotlib(ax: &Bound<'_, PyAny>, size: Option<(u32, u32)>) -> PyResult<Camera> {
        let matrix = ax.call_method0("get_proj")?;
        let size = match size {
            Some(s) => s,
            None => {
                let bbox = ax.getattr("bbox")?;
                let w: f64 = bbox.getattr("width")?.extract()?;
                let h: f64 = bbox.getattr("height")?.extract()?;
                (w.round().max(1.0) as u32, h.round().max(1.0) as u32)
            }
        };
        Camera::from_matrix(&matrix, size)
    }

    /// Image size in pixels: (width, height).
    #[getter]
    fn size(&self) -> (u32, u32) {
        self.spec.size.unwrap_or(sightline::camera::DEFAULT_SIZE)
    }

    fn __repr__(&self) -> String {
        let s = &self.spec;
        if let Some(m) = self.projection {
            return format!("Camera(matrix={m:?}, size={:?})", self.size());
        }
        format!(
            "Camera(eye={:?}, target={:?}, up={:?}, fov={:?}, ortho={:?}, size={:?}, view={:?})",
            s.eye.map(|v| v.to_array()),
            s.target.map(|v| v.to_array()),
            s.up.map(|v| v.to_array()),
            s.fovy_deg,
            s.ortho_height,
            self.size(),
            s.view
        )
    }
}

fn named_view(name: &str) -> PyResult<NamedView> {
    Ok(match name {
        "front" => NamedView::Front,
        "back" => NamedView::Back,
        "top" => NamedView::Top,
        "bottom" => NamedView::Bottom,
        "left" => NamedView::Left,
        "right" => NamedView::Right,
        "iso" => NamedView::Iso,
        other => {
            return Err(err(format!(
                "view must be front, back, top, bottom, left, right or iso (got {other:?})"
            )));
        }
    })
}

/// One visible region of one face: its outer boundary and its holes, in pixels (y down).
#[pyclass(frozen, module = "sightline")]
struct Region {
    /// The input face id.
    #[pyo3(get)]
    face: u32,
    /// Shaded colour, linear RGB in [0, 1].
    #[pyo3(get)]
    color: (f64, f64, f64),
    /// 1 - transparency.
    #[pyo3(get)]
    opacity: f64,
    rings: Vec<Vec<[f64; 2]>>,
}

#[pymethods]
impl Region {
    /// The rings, each a (k, 2) float64 array of points (pixels, y down, unless `coords` asked
    /// for others; not closed: the last point is not repeated); the first is the outer
    /// boundary, the rest are holes. In pixels, outer rings have a positive signed area (x
    /// right, y down: clockwise as seen) and holes a negative one; in projected coordinates (y
    /// up) the signs are the other way round.
    #[getter]
    fn rings<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        self.rings.iter().map(|r| ring_array(py, r)).collect()
    }

    /// The outer boundary: `rings[0]`.
    #[getter]
    fn outer<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        ring_array(py, &self.rings[0])
    }

    /// The holes: `rings[1:]`.
    #[getter]
    fn holes<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        self.rings[1..].iter().map(|r| ring_array(py, r)).collect()
    }

    /// The region's area in square pixels (outer less holes).
    #[getter]
    fn area(&self) -> f64 {
        self.rings.iter().map(|r| signed_area(r)).sum::<f64>().abs()
    }

    fn __repr__(&self) -> String {
        format!(
            "Region(face={}, {} points, {} holes)",
            self.face,
            self.rings[0].len(),
            self.rings.len() - 1
        )
    }
}

fn ring_array<'py>(py: Python<'py>, ring: &[[f64; 2]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = ring.iter().flatten().copied().collect();
    numpy::PyArray1::from_vec(py, flat).reshape([ring.len(), 2])
}

/// The signed area on the numbers as written (positive for outer rings in pixels).
fn signed_area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// A drawing item's rings as regions of one outer ring each, its holes after it (an item may
/// hold an island inside a hole): as the canonical form decides holes.
fn regions_of_item(item: &DrawItem) -> Vec<Vec<Ring>> {
    regions_of_rings(&item.rings)
        .into_iter()
        .map(|region| region.into_iter().map(|k| item.rings[k].clone()).collect())
        .collect()
}

/// A closed ring of pixel points (the last not repeated).
type Ring = Vec<[f64; 2]>;

fn exact_strategy(name: &str) -> PyResult<&'static dyn sightline::Strategy> {
    let exact = |m: &methods::Method| m.exact && !m.is_image_space();
    match methods::method(name).filter(|m| exact(m)).map(|m| m.engine) {
        Some(Engine::Object(strategy)) => Ok(strategy),
        _ => Err(err(format!(
            "method {name:?} computes no exact visible regions: use {}",
            methods::names_with(exact)
        ))),
    }
}

/// Maps pixel points to the coordinates asked for: "pixel" as they are, "projected" through a
/// projection camera's frame.
fn coordinates(coords: &str, frame: Option<Frame>) -> PyResult<impl Fn([f64; 2]) -> [f64; 2]> {
    let frame = match (coords, frame) {
        ("pixel", _) => None,
        ("projected", Some(f)) => Some(f),
        ("projected", None) => {
            return Err(err(
                "coords=\"projected\" needs a projection camera (Camera.from_matrix or Camera.from_matplotlib)",
            ));
        }
        (other, _) => {
            return Err(err(format!(
                "coords must be \"pixel\" or \"projected\" (got {other:?})"
            )));
        }
    };
    Ok(move |p| frame.map_or(p, |f| f.point(p)))
}

/// The exact visible regions of `scene` seen by `camera`: one `Region` per connected visible
/// part of a face, in drawing order (back to front). `method`: any exact strategy ("auto",
/// "coverage", "bsp", "newell", "weiler-atherton", "warnock-exact"): all give the same
/// regions. `coords`: "pixel" (y down), or "projected" for a projection camera (its projected
/// x and y: matplotlib's 2D drawing coordinates for `Camera.from_matplotlib`).
#[pyfunction]
#[pyo3(signature = (scene, camera, method = "auto", coords = "pixel"))]
fn visible_set(
    py: Python<'_>,
    scene: &Scene,
    camera: &Camera,
    method: &str,
    coords: &str,
) -> PyResult<Vec<Region>> {
    let strategy = exact_strategy(method)?;
    let scene = scene.inner.clone();
    let camera = camera.clone();
    let (drawing, frame) = py
        .detach(move || -> Result<_, String> {
            let placed = camera.place(&scene)?;
            let prepared = pipeline::prepare(&placed.scene, &placed.camera, CullMode::Auto);
            let picture = draw::picture(
                strategy,
                &placed.scene,
                &prepared.screen,
                &placed.camera,
                Fill::Shade,
                DrawOptions::per_face(),
                None,
            );
            Ok((picture.drawing, placed.frame))
        })
        .map_err(err)?;
    let map = coordinates(coords, frame)?;
    Ok(drawing
        .items
        .iter()
        .flat_map(|item| {
            regions_of_item(item).into_iter().map(|rings| Region {
                face: item.face,
                color: (item.color[0], item.color[1], item.color[2]),
                opacity: item.opacity,
                rings: rings
                    .into_iter()
                    .map(|r| r.into_iter().map(&map).collect())
                    .collect(),
            })
        })
        .collect())
}

/// One stroke of a line drawing.
#[pyclass(frozen, module = "sightline")]
struct Stroke {
    /// "silhouette", "boundary", "intersection", "crease" or "material".
    #[pyo3(get)]
    kind: &'static str,
    /// Seen (no face in front of it) or hidden.
    #[pyo3(get)]
    visible: bool,
    /// How many faces lie in front of it (0 when visible; 1, "at least one", for every hidden
    /// stroke unless `qi_max` was given).
    #[pyo3(get)]
    qi: u32,
    /// Whether the last point joins back to the first.
    #[pyo3(get)]
    closed: bool,
    points: Vec<[f64; 2]>,
}

#[pymethods]
impl Stroke {
    /// The polyline, a (k, 2) float64 array of points (pixels, y down, unless `coords` asked
    /// for others).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        ring_array(py, &self.points)
    }

    fn __repr__(&self) -> String {
        format!(
            "Stroke({} {}, {} points{})",
            if self.visible { "visible" } else { "hidden" },
            self.kind,
            self.points.len(),
            if self.closed { ", closed" } else { "" }
        )
    }
}

/// The hidden-line drawing of `scene` seen by `camera`: visible and (with `hidden`) hidden
/// strokes of silhouettes, boundaries, intersections, creases (edges whose faces' normals
/// differ by more than `crease` degrees) and material edges. `qi_max`: hidden strokes only up
/// to that many faces deep, each with its exact count.
#[pyfunction]
#[pyo3(signature = (scene, camera, hidden = true, crease = 30.0, qi_max = None, coords = "pixel"))]
fn lines(
    py: Python<'_>,
    scene: &Scene,
    camera: &Camera,
    hidden: bool,
    crease: f64,
    qi_max: Option<u32>,
    coords: &str,
) -> PyResult<Vec<Stroke>> {
    if !(0.0..=180.0).contains(&crease) {
        return Err(err(format!(
            "crease must be in [0, 180] degrees (got {crease})"
        )));
    }
    let options = LineOptions {
        crease_deg: crease,
        hidden,
        qi_max,
        cull: CullMode::Auto,
    };
    let scene = scene.inner.clone();
    let camera = camera.clone();
    let (drawn, frame) = py
        .detach(move || -> Result<_, String> {
            let placed = camera.place(&scene)?;
            let drawn = line_drawing(&placed.scene, &placed.camera, &options, None)
                .map_err(|e| e.to_string())?;
            Ok((drawn, placed.frame))
        })
        .map_err(err)?;
    let map = coordinates(coords, frame)?;
    Ok(drawn
        .drawing
        .strokes
        .into_iter()
        .map(|s| Stroke {
            kind: s.kind.name(),
            visible: s.visibility == sightline::lines::Visibility::Visible,
            qi: s.qi,
            closed: s.closed,
            points: s.points.into_iter().map(&map).collect(),
        })
        .collect())
}

/// The picture as `sightline render` writes it, in memory.
fn rendered(
    py: Python<'_>,
    scene: &Scene,
    camera: &Camera,
    format: Output,
    method: Option<&str>,
    with_lines: bool,
) -> PyResult<Vec<u8>> {
    let mut options = RenderOptions::new(format);
    if let Some(name) = method {
        let m = methods::method(name).ok_or_else(|| {
            err(format!(
                "no method {name:?}: use {}",
                methods::names_with(|_| true)
            ))
        })?;
        options = options.with_method(m);
    }
    if with_lines {
        options.lines = Some(LineOptions::default());
    }
    let scene = scene.inner.clone();
    let camera = camera.clone();
    let (bytes, warnings) = py
        .detach(move || -> Result<(Vec<u8>, Vec<String>), String> {
            let placed = camera.place(&scene)?;
            let prepared = pipeline::prepare(&placed.scene, &placed.camera, CullMode::Auto);
            let picture = render::render(
                &placed.scene,
                &placed.camera,
                &prepared.screen,
                &options,
                None,
            )
            .map_err(|e| e.to_string())?;
            let mut bytes = Vec::new();
            picture.write(&mut bytes).map_err(|e| e.to_string())?;
            Ok((bytes, picture.warnings))
        })
        .map_err(err)?;
    // What the command prints as warnings (an empty view, translucent faces drawn opaque).
    for w in warnings {
        let w = keywords(&w);
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyUserWarning>(),
            &std::ffi::CString::new(w).unwrap_or_default(),
            1,
        )?;
    }
    Ok(bytes)
}

/// The SVG picture (exact visible regions, seamless), as a string. `lines`: the visible lines
/// drawn over the fills.
#[pyfunction]
#[pyo3(signature = (scene, camera, method = None, lines = false))]
fn to_svg(
    py: Python<'_>,
    scene: &Scene,
    camera: &Camera,
    method: Option<&str>,
    lines: bool,
) -> PyResult<String> {
    let bytes = rendered(py, scene, camera, Output::Svg, method, lines)?;
    String::from_utf8(bytes).map_err(err)
}

/// The PNG picture, as bytes (the z-buffer unless `method` names another).
#[pyfunction]
#[pyo3(signature = (scene, camera, method = None))]
fn to_png<'py>(
    py: Python<'py>,
    scene: &Scene,
    camera: &Camera,
    method: Option<&str>,
) -> PyResult<Bound<'py, PyBytes>> {
    let bytes = rendered(py, scene, camera, Output::Png, method, false)?;
    Ok(PyBytes::new(py, &bytes))
}

/// The names of the methods: every one, or the exact ones that `visible_set` takes.
#[pyfunction]
#[pyo3(signature = (exact = false))]
fn method_names(exact: bool) -> Vec<&'static str> {
    methods::METHODS
        .iter()
        .filter(|m| !exact || (m.exact && !m.is_image_space()))
        .map(|m| m.name)
        .collect()
}

#[pymodule]
fn _sightline(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SightlineError", m.py().get_type::<SightlineError>())?;
    m.add_class::<Scene>()?;
    m.add_class::<Camera>()?;
    m.add_class::<Region>()?;
    m.add_class::<Stroke>()?;
    m.add_function(wrap_pyfunction!(visible_set, m)?)?;
    m.add_function(wrap_pyfunction!(lines, m)?)?;
    m.add_function(wrap_pyfunction!(to_svg, m)?)?;
    m.add_function(wrap_pyfunction!(to_png, m)?)?;
    m.add_function(wrap_pyfunction!(method_names, m)?)?;
    Ok(())
}
