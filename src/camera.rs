//! The camera: OpenGL conventions throughout.
//!
//! - World space is right-handed. The view matrix is gluLookAt(eye, target, up): the camera looks
//!   down its -z axis with `up` projected to its +y.
//! - The projection is gluPerspective(fovy, aspect, near, far) or glOrtho(-h·aspect/2, h·aspect/2,
//!   -h/2, h/2, near, far), aspect = width / height. Clip space is OpenGL's: a point is inside when
//!   -w <= x, y, z <= w; NDC z is -1 at the near plane and +1 at the far plane.
//! - NDC \[-1,1\]² maps to the image \[0,W\] x \[0,H\] with y growing downward: pixel (i, j) has its
//!   centre at x = i + 0.5, y = j + 0.5, which is NDC ((2i+1)/W - 1, 1 - (2j+1)/H).
//!
//! A `Camera` is valid (see [`Camera::validate`]) before any projection uses it.

use crate::error::Error;
use glam::dcamera::{self, rh::proj::opengl as gl};
use glam::{DMat4, DQuat, DVec3};

/// How the view volume is shaped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A perspective view (gluPerspective).
    Perspective {
        /// Vertical field of view in degrees.
        fovy_deg: f64,
    },
    /// A parallel view (glOrtho).
    Orthographic {
        /// Height of the view volume in world units.
        height: f64,
    },
}

/// Named views, fitted to a bounding box (world +y is up, +z toward the front viewer).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum NamedView {
    /// From +z, y up.
    Front,
    /// From -z, y up.
    Back,
    /// From +y, -z up.
    Top,
    /// From -y, +z up.
    Bottom,
    /// From -x, y up.
    Left,
    /// From +x, y up.
    Right,
    /// From (1, 1, 1), y up.
    Iso,
}

impl NamedView {
    /// Direction from the target to the eye, and the up vector.
    pub fn direction_and_up(self) -> (DVec3, DVec3) {
        match self {
            NamedView::Front => (DVec3::Z, DVec3::Y),
            NamedView::Back => (DVec3::NEG_Z, DVec3::Y),
            NamedView::Top => (DVec3::Y, DVec3::NEG_Z),
            NamedView::Bottom => (DVec3::NEG_Y, DVec3::Z),
            NamedView::Left => (DVec3::NEG_X, DVec3::Y),
            NamedView::Right => (DVec3::X, DVec3::Y),
            NamedView::Iso => (DVec3::ONE.normalize(), DVec3::Y),
        }
    }
}

/// Default vertical field of view for fitted perspective views, degrees.
pub const DEFAULT_FOVY_DEG: f64 = 40.0;

/// A camera with its image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Where the camera is (world space).
    pub eye: DVec3,
    /// The point it looks at.
    pub target: DVec3,
    /// The direction that appears up in the image (need not be orthogonal to the view).
    pub up: DVec3,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Distance of the near clipping plane along the view (may be negative when orthographic).
    pub near: f64,
    /// Distance of the far clipping plane, beyond `near`.
    pub far: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// Largest image side: keeps every exact pixel-sample computation inside its bit budget
/// (see `exact`).
pub const MAX_IMAGE_SIDE: u32 = 16384;

impl Camera {
    /// Width over height.
    pub fn aspect(&self) -> f64 {
        self.width as f64 / self.height as f64
    }

    /// World to camera space: gluLookAt(eye, target, up).
    pub fn view_matrix(&self) -> DMat4 {
        dcamera::rh::view::look_at_mat4(self.eye, self.target, self.up)
    }

    /// Camera to clip space: gluPerspective or glOrtho.
    pub fn projection_matrix(&self) -> DMat4 {
        match self.projection {
            Projection::Perspective { fovy_deg } => {
                gl::perspective(fovy_deg.to_radians(), self.aspect(), self.near, self.far)
            }
            Projection::Orthographic { height } => {
                let hw = height * self.aspect() / 2.0;
                let hh = height / 2.0;
                gl::orthographic(-hw, hw, -hh, hh, self.near, self.far)
            }
        }
    }

    /// World to clip space.
    pub fn view_projection(&self) -> DMat4 {
        self.projection_matrix() * self.view_matrix()
    }

    /// Unit vector the camera looks along.
    pub fn forward(&self) -> DVec3 {
        (self.target - self.eye).normalize()
    }

    /// Is the projection a perspective one?
    pub fn is_perspective(&self) -> bool {
        matches!(self.projection, Projection::Perspective { .. })
    }

    /// Checks that the camera defines a proper view volume.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |m: String| Err(Error::Camera(m));
        // First: a zero side gives a zero aspect, and whatever was fitted with it is infinite.
        if self.width == 0
            || self.height == 0
            || self.width > MAX_IMAGE_SIDE
            || self.height > MAX_IMAGE_SIDE
        {
            return bad(format!(
                "image size {}x{} must be between 1 and {MAX_IMAGE_SIDE} on each side",
                self.width, self.height
            ));
        }
        for (name, v) in [("eye", self.eye), ("target", self.target), ("up", self.up)] {
            if !v.is_finite() {
                return bad(format!("camera {name} is not finite: {v}"));
            }
        }
        let dir = self.target - self.eye;
        if dir.length_squared() == 0.0 {
            return bad("camera eye and target are the same point".into());
        }
        if dir.cross(self.up).length_squared() == 0.0 {
            return bad("camera up vector is zero or parallel to the view direction".into());
        }
        if !(self.near.is_finite() && self.far.is_finite() && self.far > self.near) {
            return bad(format!(
                "need near < far, both finite (near {}, far {})",
                self.near, self.far
            ));
        }
        match self.projection {
            Projection::Perspective { fovy_deg } => {
                if self.near <= 0.0 {
                    return bad(format!("perspective needs near > 0 (near {})", self.near));
                }
                if !(fovy_deg > 0.0 && fovy_deg < 180.0) {
                    return bad(format!(
                        "field of view must be in (0, 180) degrees (got {fovy_deg})"
                    ));
                }
            }
            Projection::Orthographic { height } => {
                if !(height > 0.0 && height.is_finite()) {
                    return bad(format!("orthographic height must be > 0 (got {height})"));
                }
            }
        }
        Ok(())
    }

    /// A camera looking along a named view at the bounding box `(lo, hi)`, framing all of it.
    pub fn fit(
        view: NamedView,
        bounds: (DVec3, DVec3),
        orthographic: bool,
        fovy_deg: f64,
        width: u32,
        height: u32,
    ) -> Camera {
        let (dir, up) = view.direction_and_up();
        let (center, radius) = bounding_sphere(bounds);
        let aspect = width as f64 / height as f64;
        let margin = 1.05;
        let projection = if orthographic {
            Projection::Orthographic {
                height: 2.0 * radius * margin / aspect.min(1.0),
            }
        } else {
            Projection::Perspective { fovy_deg }
        };
        let half_fov = {
            let fy = (fovy_deg / 2.0).to_radians();
            let fx = (fy.tan() * aspect).atan();
            fy.min(fx)
        };
        let distance = if orthographic {
            radius * 2.0
        } else {
            radius * margin / half_fov.sin()
        };
        let eye = center + dir * distance;
        let mut cam = Camera {
            eye,
            target: center,
            up,
            projection,
            near: 0.0,
            far: 1.0,
            width,
            height,
        };
        cam.fit_depth_range(bounds);
        cam
    }

    /// Sets near and far to enclose the bounding box seen from the current eye, with a margin.
    /// When the eye is inside the box the near plane is put at a thousandth of the far distance.
    pub fn fit_depth_range(&mut self, bounds: (DVec3, DVec3)) {
        let (center, radius) = bounding_sphere(bounds);
        let forward = self.forward();
        let along = (center - self.eye).dot(forward);
        let far = (along + radius * 1.1)
            .max(radius * 1e-3)
            .max(f64::MIN_POSITIVE);
        let near = along - radius * 1.1;
        self.far = far;
        self.near = if self.is_perspective() {
            near.max(far * 1e-3)
        } else {
            near
        };
    }

    /// The camera of an X3D Viewpoint, with near and far fitted to the bounding box.
    /// X3D's fieldOfView is the smaller of the two angles; our fovy is the vertical one.
    pub fn from_viewpoint(
        vp: &crate::scene::Viewpoint,
        bounds: (DVec3, DVec3),
        width: u32,
        height: u32,
    ) -> Camera {
        let rot = if vp.orientation_axis.length_squared() > 0.0 {
            DQuat::from_axis_angle(vp.orientation_axis.normalize(), vp.orientation_angle)
        } else {
            DQuat::IDENTITY
        };
        let forward = rot * DVec3::NEG_Z;
        let up = rot * DVec3::Y;
        let aspect = width as f64 / height as f64;
        let fov = vp.field_of_view;
        let fovy = if aspect >= 1.0 {
            fov
        } else {
            2.0 * ((fov / 2.0).tan() / aspect).atan()
        };
        let mut cam = Camera {
            eye: vp.position,
            target: vp.position + forward,
            up,
            projection: Projection::Perspective {
                fovy_deg: fovy.to_degrees(),
            },
            near: 0.1,
            far: 100.0,
            width,
            height,
        };
        cam.fit_depth_range(bounds);
        cam
    }

    /// Pixel centre (i, j) in NDC.
    pub fn pixel_center_ndc(&self, i: u32, j: u32) -> (f64, f64) {
        (
            (2 * i + 1) as f64 / self.width as f64 - 1.0,
            1.0 - (2 * j + 1) as f64 / self.height as f64,
        )
    }

    /// The world-space ray through an NDC point: origin on the near plane and unit direction.
    pub fn ray_through_ndc(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let inv = self.view_projection().inverse();
        let a = inv.project_point3(DVec3::new(x, y, -1.0));
        let b = inv.project_point3(DVec3::new(x, y, 1.0));
        (a, (b - a).normalize())
    }
}

/// A camera as the user asked for it: every part optional, resolved against a scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CameraSpec {
    /// A camera file (`--cam`), the starting point when given ([`CamFile::read`]).
    pub cam_file: Option<CamFile>,
    /// A named view fitted to the scene's bounds (`--view`).
    pub view: Option<NamedView>,
    /// The eye (`--eye`).
    pub eye: Option<DVec3>,
    /// The point looked at (`--target`).
    pub target: Option<DVec3>,
    /// The up direction (`--up`).
    pub up: Option<DVec3>,
    /// Perspective with this vertical field of view, degrees (`--fov`).
    pub fovy_deg: Option<f64>,
    /// Orthographic with this view height (`--ortho`).
    pub ortho_height: Option<f64>,
    /// Near plane distance (`--near`); fitted to the scene when not given.
    pub near: Option<f64>,
    /// Far plane distance (`--far`); fitted to the scene when not given.
    pub far: Option<f64>,
    /// Image size, width and height (`--size`); [`DEFAULT_SIZE`] when not given.
    pub size: Option<(u32, u32)>,
}

/// Image size when none is given.
pub const DEFAULT_SIZE: (u32, u32) = (1024, 1024);

impl CameraSpec {
    /// Checks each numeric part within its own range, before a camera is built (where a bad
    /// value would surface as some other part's error). The messages name the command line's
    /// flags; `cam_path` names the camera file.
    pub fn check(&self, cam_path: Option<&std::path::Path>) -> Result<(), Error> {
        let bad = |m: String| Err(Error::Camera(m));
        if let Some(f) = self.fovy_deg
            && !(f > 0.0 && f < 180.0)
        {
            return bad(format!("--fov must be in (0, 180) degrees (got {f})"));
        }
        if let Some(h) = self.ortho_height
            && !(h > 0.0 && h.is_finite())
        {
            return bad(format!("--ortho must be a view height > 0 (got {h})"));
        }
        for (flag, v) in [("--near", self.near), ("--far", self.far)] {
            if let Some(v) = v
                && !v.is_finite()
            {
                return bad(format!("{flag} must be a finite distance (got {v})"));
            }
        }
        let from_file_ortho = self
            .cam_file
            .is_some_and(|c| matches!(c.projection(), Projection::Orthographic { .. }));
        let perspective =
            self.ortho_height.is_none() && (self.fovy_deg.is_some() || !from_file_ortho);
        for (flag, v) in [("--near", self.near), ("--far", self.far)] {
            if let Some(v) = v
                && perspective
                && v <= 0.0
            {
                return bad(format!(
                    "{flag} must be > 0 for a perspective camera (got {v}; orthographic views, --ortho, take any value)"
                ));
            }
        }
        if let (Some(n), Some(f)) = (self.near, self.far)
            && f <= n
        {
            return bad(format!(
                "--near must be less than --far (near {n}, far {f})"
            ));
        }
        // An orthographic camera file may put its near plane behind the eye; made perspective by
        // --fov, it needs a near plane in front.
        if let Some(file) = self.cam_file
            && perspective
            && self.near.is_none()
            && file.near <= 0.0
        {
            let name = cam_path.map_or("the camera file".into(), |p| p.display().to_string());
            return bad(format!(
                "{name}: near {} is not > 0: --fov makes the camera perspective, which needs a near plane in front of the eye (give --near)",
                file.near
            ));
        }
        Ok(())
    }

    /// [`Self::resolve`] against `scene`: its bounds and its own viewpoint.
    pub fn resolve_for(&self, scene: &crate::scene::Scene) -> Result<Camera, Error> {
        let bounds = scene
            .bounds()
            .ok_or_else(|| Error::Camera(format!("{}: no face to look at", scene.source)))?;
        self.resolve(bounds, scene.viewpoint.as_ref())
    }

    /// The camera, in this order of precedence: a camera file; a named view fitted to the scene;
    /// an explicit eye/target; the scene's own viewpoint; the iso view fitted to the scene. Then
    /// explicit eye, target, up, projection, near and far override; near and far not given are
    /// fitted to the scene's bounds from the final eye.
    pub fn resolve(
        &self,
        bounds: (DVec3, DVec3),
        viewpoint: Option<&crate::scene::Viewpoint>,
    ) -> Result<Camera, Error> {
        let (w, h) = self
            .size
            .or(self.cam_file.map(|c| c.size))
            .unwrap_or(DEFAULT_SIZE);
        let fovy = self.fovy_deg.unwrap_or(DEFAULT_FOVY_DEG);
        let ortho = self.ortho_height.is_some();
        let explicit_pose = self.eye.is_some() || self.target.is_some();
        let mut cam = if let Some(file) = &self.cam_file {
            let mut c = file.camera();
            c.width = w;
            c.height = h;
            c
        } else if let Some(view) = self.view {
            Camera::fit(view, bounds, ortho, fovy, w, h)
        } else if let (false, Some(vp)) = (explicit_pose, viewpoint) {
            Camera::from_viewpoint(vp, bounds, w, h)
        } else {
            Camera::fit(NamedView::Iso, bounds, ortho, fovy, w, h)
        };
        if let Some(e) = self.eye {
            cam.eye = e;
        }
        if let Some(t) = self.target {
            cam.target = t;
        }
        if let Some(u) = self.up {
            cam.up = u;
        }
        if let Some(f) = self.fovy_deg {
            cam.projection = Projection::Perspective { fovy_deg: f };
        }
        if let Some(hgt) = self.ortho_height {
            cam.projection = Projection::Orthographic { height: hgt };
        }
        let refit = explicit_pose && self.cam_file.is_none()
            || self.near.is_none() && self.far.is_none() && self.cam_file.is_none();
        if refit && cam.target != cam.eye {
            cam.fit_depth_range(bounds);
            let (center, radius) = bounding_sphere(bounds);
            if self.near.is_none() && self.far.is_none() && cam.far <= cam.near {
                // The scene's depth vanishes when rounded at the eye's distance: near and far,
                // which the user did not give, round to one value.
                return Err(Error::Camera(format!(
                    "the eye is too far from the scene to resolve its depth (distance {:.3e}, scene radius {:.3e}): move the eye closer",
                    (center - cam.eye).length(),
                    radius
                )));
            }
        }
        if let Some(n) = self.near {
            cam.near = n;
        }
        if let Some(f) = self.far {
            cam.far = f;
        }
        cam.validate()?;
        Ok(cam)
    }
}

/// Centre and radius of the sphere around an axis-aligned box (radius never zero).
pub fn bounding_sphere((lo, hi): (DVec3, DVec3)) -> (DVec3, f64) {
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-9 * center.abs().max_element().max(1.0));
    (center, radius)
}

/// A camera file as in `../shared/meshes/cams/*.cam` (written by `../shared/compare/scenes.py`):
/// lines `eye x y z`, `target x y z`, `up x y z`, `fovy DEG`, `ortho_height H`, `near N`,
/// `far F`, `size W H`; `#` starts a comment line. `fovy 0` means orthographic with view height
/// `ortho_height`; otherwise the camera is a perspective one and `ortho_height` is unused.
/// A leading UTF-8 byte-order mark and CRLF line ends are accepted.
///
/// A parsed file is a valid camera: every error names the file and, where one line is to blame,
/// that line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CamFile {
    /// `eye x y z`.
    pub eye: DVec3,
    /// `target x y z`.
    pub target: DVec3,
    /// `up x y z`.
    pub up: DVec3,
    /// Vertical field of view in degrees; 0 for orthographic.
    pub fovy_deg: f64,
    /// `ortho_height H`: the view height when `fovy` is 0.
    pub ortho_height: Option<f64>,
    /// `near N`.
    pub near: f64,
    /// `far F`.
    pub far: f64,
    /// `size W H` ([`DEFAULT_SIZE`] when the file has none).
    pub size: (u32, u32),
}

impl CamFile {
    /// Reads and parses the camera file at `path` (errors name it, and the line).
    pub fn read(path: &std::path::Path) -> Result<CamFile, Error> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: name.clone(),
            source,
        })?;
        Ok(CamFile::parse(&text, &name)?)
    }

    /// Parses the text of a camera file called `name` (for messages).
    pub fn parse(text: &str, name: &str) -> Result<CamFile, crate::LoadError> {
        use crate::LoadError;
        // Each key's values and the line they came from.
        let mut seen: std::collections::HashMap<&str, (Vec<f64>, usize)> = Default::default();
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        for (n, line) in text.lines().enumerate() {
            let ln = n + 1;
            let mut it = line.split_whitespace();
            let Some(key) = it.next() else { continue };
            if key.starts_with('#') {
                continue;
            }
            let vals: Vec<f64> = it
                .map(|t| {
                    t.parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| LoadError::line(name, ln, format!("bad number '{t}'")))
                })
                .collect::<Result<_, _>>()?;
            let want = match key {
                "eye" | "target" | "up" => 3,
                "fovy" | "ortho_height" | "near" | "far" => 1,
                "size" => 2,
                _ => return Err(LoadError::line(name, ln, format!("unknown key '{key}'"))),
            };
            if vals.len() != want {
                return Err(LoadError::line(
                    name,
                    ln,
                    format!("'{key}' needs {want} values, found {}", vals.len()),
                ));
            }
            seen.insert(key, (vals, ln));
        }
        let get = |k: &str| seen.get(k).map(|(v, ln)| (v.as_slice(), *ln));
        let need =
            |k: &str| get(k).ok_or_else(|| LoadError::file(name, format!("missing '{k}' line")));
        let vec3 = |k: &str| need(k).map(|(v, ln)| (DVec3::new(v[0], v[1], v[2]), ln));
        let (eye, _) = vec3("eye")?;
        let (target, target_ln) = vec3("target")?;
        let (up, up_ln) = vec3("up")?;
        let (near, near_ln) = need("near").map(|(v, ln)| (v[0], ln))?;
        let (far, far_ln) = need("far").map(|(v, ln)| (v[0], ln))?;
        let fovy = get("fovy").map(|(v, ln)| (v[0], ln));
        let ortho = get("ortho_height").map(|(v, ln)| (v[0], ln));
        let bad = |ln: usize, m: String| Err(LoadError::line(name, ln, m));
        if target == eye {
            return bad(target_ln, "target is the eye: no view direction".into());
        }
        if (target - eye).cross(up).length_squared() == 0.0 {
            return bad(up_ln, "up is zero or parallel to the view direction".into());
        }
        let fovy_deg = match fovy {
            Some((0.0, ln)) => match ortho {
                Some((h, _)) if h > 0.0 => 0.0,
                Some((h, hln)) => return bad(hln, format!("ortho_height must be > 0 (got {h})")),
                None => {
                    return bad(
                        ln,
                        "fovy 0 (orthographic) needs an 'ortho_height' line".into(),
                    );
                }
            },
            Some((f, ln)) if !(f > 0.0 && f < 180.0) => {
                return bad(
                    ln,
                    format!("fovy must be in (0, 180) degrees, or 0 for orthographic (got {f})"),
                );
            }
            Some((f, _)) => f,
            None => DEFAULT_FOVY_DEG,
        };
        if fovy_deg > 0.0 && near <= 0.0 {
            return bad(
                near_ln,
                format!("a perspective camera needs near > 0 (got {near})"),
            );
        }
        if far <= near {
            return bad(
                far_ln,
                format!("far must be beyond near (near {near}, far {far})"),
            );
        }
        let size = match get("size") {
            None => DEFAULT_SIZE,
            Some((v, ln)) => {
                let side = |x: f64| {
                    (x >= 1.0 && x.fract() == 0.0 && x <= MAX_IMAGE_SIDE as f64).then_some(x as u32)
                };
                match (side(v[0]), side(v[1])) {
                    (Some(w), Some(h)) => (w, h),
                    _ => {
                        return bad(
                            ln,
                            format!("size must be two integers in 1..={MAX_IMAGE_SIDE}"),
                        );
                    }
                }
            }
        };
        Ok(CamFile {
            eye,
            target,
            up,
            fovy_deg,
            ortho_height: ortho.map(|(h, _)| h),
            near,
            far,
            size,
        })
    }

    /// The file's projection: orthographic when `fovy` is 0.
    pub fn projection(&self) -> Projection {
        match self.ortho_height {
            Some(height) if self.fovy_deg == 0.0 => Projection::Orthographic { height },
            _ => Projection::Perspective {
                fovy_deg: self.fovy_deg,
            },
        }
    }

    /// The camera the file describes, at its size.
    pub fn camera(&self) -> Camera {
        Camera {
            eye: self.eye,
            target: self.target,
            up: self.up,
            projection: self.projection(),
            near: self.near,
            far: self.far,
            width: self.size.0,
            height: self.size.1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_depths_follow_gl_perspective() {
        // Seed 002: eye at z=8 looking down -z, near 5, far 10: z=0 maps to NDC 0.5, z=-1 to 7/9.
        let cam = Camera {
            eye: DVec3::new(0., 0., 8.),
            target: DVec3::ZERO,
            up: DVec3::Y,
            projection: Projection::Perspective { fovy_deg: 45.0 },
            near: 5.0,
            far: 10.0,
            width: 12,
            height: 10,
        };
        let m = cam.view_projection();
        let z0 = m.project_point3(DVec3::new(1., 0., 0.)).z;
        let z1 = m.project_point3(DVec3::new(-1., 0., -1.)).z;
        assert!((z0 - 0.5).abs() < 1e-12);
        assert!((z1 - 7.0 / 9.0).abs() < 1e-12);
    }

    #[test]
    fn fitted_views_see_the_whole_box() {
        let b = (DVec3::new(-1., -2., -3.), DVec3::new(4., 5., 6.));
        for view in [
            NamedView::Front,
            NamedView::Back,
            NamedView::Top,
            NamedView::Bottom,
            NamedView::Left,
            NamedView::Right,
            NamedView::Iso,
        ] {
            for ortho in [false, true] {
                let cam = Camera::fit(view, b, ortho, DEFAULT_FOVY_DEG, 300, 200);
                cam.validate().unwrap();
                let m = cam.view_projection();
                for k in 0..8 {
                    let p = DVec3::new(
                        if k & 1 == 0 { b.0.x } else { b.1.x },
                        if k & 2 == 0 { b.0.y } else { b.1.y },
                        if k & 4 == 0 { b.0.z } else { b.1.z },
                    );
                    let q = m.project_point3(p);
                    assert!(
                        q.abs().max_element() <= 1.0,
                        "{view:?} ortho={ortho}: corner {p} at NDC {q}"
                    );
                }
            }
        }
    }

    #[test]
    fn viewpoint_fov_is_the_smaller_angle() {
        let vp = crate::scene::Viewpoint {
            position: DVec3::new(0., 0., 10.),
            orientation_axis: DVec3::Z,
            orientation_angle: 0.0,
            field_of_view: std::f64::consts::FRAC_PI_4,
        };
        let b = (DVec3::splat(-1.), DVec3::splat(1.));
        let wide = Camera::from_viewpoint(&vp, b, 200, 100);
        let tall = Camera::from_viewpoint(&vp, b, 100, 200);
        let Projection::Perspective { fovy_deg: w } = wide.projection else {
            panic!()
        };
        let Projection::Perspective { fovy_deg: t } = tall.projection else {
            panic!()
        };
        assert!((w - 45.0).abs() < 1e-9);
        // Tall image: the horizontal angle is 45 degrees, so the vertical one is wider.
        let fx = 2.0 * ((t.to_radians() / 2.0).tan() * 0.5).atan();
        assert!((fx.to_degrees() - 45.0).abs() < 1e-9);
        assert_eq!(wide.forward(), DVec3::NEG_Z);
    }

    #[test]
    fn cam_file_round_trip() {
        let text = "eye 1 2 3\ntarget 0 0 0\nup 0 1 0\nfovy 40\northo_height 2.5\nnear 0.1\nfar 10\nsize 640 480\n";
        let c = CamFile::parse(text, "x.cam").unwrap();
        assert_eq!(c.size, (640, 480));
        assert_eq!(
            c.camera().projection,
            Projection::Perspective { fovy_deg: 40.0 }
        );
        let e = CamFile::parse("eye 1 2\n", "x.cam").unwrap_err();
        assert_eq!(e.location, crate::Location::Line(1));
    }

    /// `fovy 0` is orthographic with the file's `ortho_height`, as `scenes.py` writes it.
    #[test]
    fn cam_file_fovy_zero_is_orthographic() {
        let text = "eye 0 0 10\ntarget 0 0 0\nup 0 1 0\nfovy 0\northo_height 6\nnear 0.5\nfar 100\nsize 800 800\n";
        let c = CamFile::parse(text, "cyclic_bars.cam").unwrap();
        assert_eq!(
            c.camera().projection,
            Projection::Orthographic { height: 6.0 }
        );
        c.camera().validate().unwrap();
    }

    /// A leading byte-order mark and CRLF line ends read as the plain file does.
    #[test]
    fn cam_file_skips_a_bom_and_accepts_crlf() {
        let plain = "eye 1 2 3\ntarget 0 0 0\nup 0 1 0\nfovy 30\nnear 0.1\nfar 10\nsize 64 48\n";
        let dos = format!("\u{feff}{}", plain.replace('\n', "\r\n"));
        assert_eq!(
            CamFile::parse(&dos, "dos.cam").unwrap(),
            CamFile::parse(plain, "plain.cam").unwrap()
        );
    }

    /// Every bad value is reported at its own line of the named file.
    #[test]
    fn cam_file_errors_name_file_and_line() {
        let base = [
            "eye 0 0 10",
            "target 0 0 0",
            "up 0 1 0",
            "fovy 40",
            "near 0.5",
            "far 100",
        ];
        let cases: [(usize, &str, &str); 6] = [
            (3, "fovy 0", "ortho_height"),
            (3, "fovy 180", "fovy"),
            (3, "fovy -5", "fovy"),
            (4, "near 0", "near"),
            (5, "far 0.2", "far"),
            (2, "up 0 0 1", "up"),
        ];
        for (k, line, word) in cases {
            let mut lines = base.map(String::from).to_vec();
            lines[k] = line.to_string();
            let e = CamFile::parse(&lines.join("\n"), "v.cam").unwrap_err();
            assert_eq!(e.file, "v.cam");
            assert_eq!(e.location, crate::Location::Line(k + 1), "{line}: {e}");
            assert!(e.message.contains(word), "{line}: {e}");
        }
    }

    /// An eye so far away that the scene's depth rounds away is reported as such, not as a bad
    /// near/far the user never gave.
    #[test]
    fn a_far_eye_is_named_as_the_problem() {
        let spec = CameraSpec {
            eye: Some(DVec3::splat(1e30)),
            ..Default::default()
        };
        let e = spec
            .resolve((DVec3::splat(-1.0), DVec3::splat(1.0)), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("eye is too far") && !e.contains("near <"), "{e}");
    }

    /// Each numeric part out of its range is refused by `check`, naming the flag (or the
    /// camera file), before any camera is built.
    #[test]
    fn check_names_the_flag_out_of_range() {
        let err = |spec: CameraSpec, path: Option<&str>| {
            spec.check(path.map(std::path::Path::new))
                .unwrap_err()
                .to_string()
        };
        let fov = CameraSpec {
            fovy_deg: Some(180.0),
            ..CameraSpec::default()
        };
        assert!(err(fov, None).starts_with("--fov must be in (0, 180)"));
        let ortho = CameraSpec {
            ortho_height: Some(0.0),
            ..CameraSpec::default()
        };
        assert!(err(ortho, None).starts_with("--ortho must be"));
        let behind = CameraSpec {
            near: Some(-1.0),
            ..CameraSpec::default()
        };
        assert!(err(behind, None).starts_with("--near must be > 0 for a perspective"));
        let crossed = CameraSpec {
            ortho_height: Some(2.0),
            near: Some(3.0),
            far: Some(3.0),
            ..CameraSpec::default()
        };
        assert!(err(crossed, None).starts_with("--near must be less than --far"));
        // An orthographic file whose near plane is behind the eye, made perspective by --fov.
        let file = CamFile::parse(
            "eye 0 0 5\ntarget 0 0 0\nup 0 1 0\nfovy 0\northo_height 2\nnear -1\nfar 9\n",
            "o.cam",
        )
        .unwrap();
        let spec = CameraSpec {
            cam_file: Some(file),
            fovy_deg: Some(30.0),
            ..CameraSpec::default()
        };
        assert!(err(spec.clone(), Some("o.cam")).starts_with("o.cam: near -1 is not > 0"));
        // The same file as it is: orthographic, any near plane.
        let spec = CameraSpec {
            fovy_deg: None,
            ..spec
        };
        assert!(spec.check(None).is_ok());
        assert!(CameraSpec::default().check(None).is_ok());
    }
}
