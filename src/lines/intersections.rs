//! Intersection lines: where two faces pass through each other, exactly.
//!
//! On the grid a face is its screen polygon with the depth of its support plane, so faces a and
//! b meet exactly on the screen line where their planes are at the same depth (`Line::Cut`), at
//! the points of that line inside both polygons. The segment where they meet is that line
//! clipped to both (convex parts of) polygons, decided exactly ([`clip_to_convex`]).
//!
//! Which pairs: every two screen polygons (back faces included: a hidden intersection is drawn
//! too) whose boxes overlap on screen and in depth, that share no edge (two welded vertices),
//! and whose meeting line passes strictly through both polygons. Pairs sharing one vertex are
//! included where they cross beyond it, when both lie exactly in their support planes: a face
//! whose snapped corners left one plane (a quad whose corners rounded off it) is drawn with the
//! plane through three of them, and its neighbours around a vertex seem to cross it within that
//! rounding; such pairs are left out, as not an intersection of the input. Coplanar faces have
//! no meeting line and make none.
//!
//! A face seen exactly edge-on ([`FlatFace`]: no area on screen, so no screen polygon) still
//! meets the faces that pass through it, along its screen line: there the meeting is the part
//! of that line where the other face's plane lies within the edge-on face (found exactly from
//! where the plane crosses the face's sides in 3D) and inside the other face's polygon. Edge-on
//! faces that are not convex, or are clipped, are left out.

use super::along::{At, Carrier};
use super::tracks::clip_to_convex;
use crate::exact::polygon::convex_piece_indices;
use crate::exact::predicates::Line;
use crate::exact::{GridPoint, Plane};
use crate::project::{ScreenPoly, ScreenScene};
use crate::scene::Scene;
use crate::visibility::grid::for_each_near;
use std::cmp::Ordering;

/// Two faces passing through each other.
#[derive(Clone, Debug)]
pub struct Meeting {
    /// The faces (`Scene::faces` indices), `faces[0] < faces[1]`.
    pub faces: [u32; 2],
    /// The screen line where their planes meet.
    pub line: Line,
    /// A support plane holding the meeting in 3D.
    pub depth: Plane,
    /// Where on it they meet: inside both polygons.
    pub extent: Vec<(At, At)>,
    /// One of the faces is seen edge-on (it has no visible pieces to tell where the meeting is
    /// seen).
    pub edge_on: bool,
}

/// A face seen exactly edge-on: its snapped corners, all on one screen line.
#[derive(Clone, Debug)]
pub struct FlatFace {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// Its snapped corners, in order.
    pub corners: Vec<GridPoint>,
}

/// Every meeting of two faces of `screen` (see the module docs). `weld` gives each scene
/// position its welded vertex id.
pub fn meetings(
    scene: &Scene,
    screen: &ScreenScene,
    flats: &[FlatFace],
    weld: &[u32],
) -> Vec<Meeting> {
    let polys = &screen.polys;
    let mut boxes: Vec<[f64; 4]> = polys.iter().map(|p| screen_box(screen, p)).collect();
    boxes.extend(flats.iter().map(|f| points_box(&f.corners)));
    let mut depths: Vec<[f64; 2]> = polys.iter().map(|p| depth_range(screen, p)).collect();
    depths.extend(flats.iter().map(|f| {
        let z = f.corners.iter().map(|c| c.z as f64);
        [
            z.clone().fold(f64::MAX, f64::min) - 1.0,
            z.fold(f64::MIN, f64::max) + 1.0,
        ]
    }));
    let parts: Vec<Vec<Vec<Line>>> = polys.iter().map(|p| convex_parts(screen, p)).collect();
    let welded = |face: u32| -> Vec<u32> {
        let face = &scene.faces[face as usize];
        let mut v: Vec<u32> = scene
            .face_corners(face)
            .iter()
            .map(|&c| weld[c as usize])
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let shared = |a: &[u32], b: &[u32]| b.iter().filter(|v| a.binary_search(v).is_ok()).count();
    let share_an_edge = |a: &[u32], b: &[u32]| shared(a, b) >= 2;
    // Faces whose every corner lies in their support plane.
    let planar: Vec<bool> = polys
        .iter()
        .map(|p| screen.corners(p).iter().all(|c| p.plane.value_at(*c) == 0))
        .collect();
    let n = polys.len();
    let mut out = Vec::new();
    for_each_near(
        &boxes,
        |_| true,
        |a, near| {
            if a >= n {
                let flat = &flats[a - n];
                let va = welded(flat.face);
                for &b in near.iter().filter(|&&b| b < n) {
                    let overlap_in_depth =
                        depths[a][0] <= depths[b][1] && depths[b][0] <= depths[a][1];
                    if overlap_in_depth && !share_an_edge(&va, &welded(polys[b].face)) {
                        out.extend(edge_on_meeting(flat, &polys[b], &parts[b]));
                    }
                }
                return;
            }
            let pa = &polys[a];
            let mut va: Option<Vec<u32>> = None;
            for &b in near.iter().filter(|&&b| b > a && b < n) {
                let pb = &polys[b];
                if depths[a][1] < depths[b][0] || depths[b][1] < depths[a][0] {
                    continue;
                }
                let line = Line::Cut(pa.plane, pb.plane);
                if !crosses(screen, pa, &line) || !crosses(screen, pb, &line) {
                    continue;
                }
                let va = va.get_or_insert_with(|| welded(pa.face));
                match shared(va, &welded(pb.face)) {
                    0 => {}
                    1 if planar[a] && planar[b] => {}
                    _ => continue,
                }
                let carrier = Carrier::new(line);
                let mut extent = Vec::new();
                for part_a in &parts[a] {
                    let Some(ia) = clip_to_convex(&carrier, part_a) else {
                        continue;
                    };
                    for part_b in &parts[b] {
                        if let Some(ib) = clip_to_convex(&carrier, part_b)
                            && let Some(both) = overlap(&carrier, ia, ib)
                        {
                            extent.push(both);
                        }
                    }
                }
                if !extent.is_empty() {
                    let (fa, fb) = (pa.face.min(pb.face), pa.face.max(pb.face));
                    out.push(Meeting {
                        faces: [fa, fb],
                        line,
                        depth: pa.plane,
                        extent,
                        edge_on: false,
                    });
                }
            }
        },
    );
    out
}

/// Where the edge-on face `flat` meets polygon `b` (convex parts `parts`), if they cross.
fn edge_on_meeting(flat: &FlatFace, b: &ScreenPoly, parts: &[Vec<Line>]) -> Option<Meeting> {
    let c = &flat.corners;
    // The screen line: through the two corners farthest apart along it.
    let (lo, hi) = (c.iter().min()?, c.iter().max()?);
    let line = Line::Edge(Plane::edge(*lo, *hi)?);
    let carrier = Carrier::new(line);
    // Where b's plane crosses the face's sides in 3D, exactly.
    let sign = |p: &GridPoint| b.plane.value_at(*p).cmp(&0);
    let signs: Vec<Ordering> = c.iter().map(sign).collect();
    if !signs.contains(&Ordering::Less) || !signs.contains(&Ordering::Greater) {
        return None;
    }
    let k = c.len();
    let mut crossings = Vec::new();
    for i in 0..k {
        let j = (i + 1) % k;
        if signs[i] == Ordering::Equal {
            crossings.push(At::Grid([c[i].x, c[i].y]));
        } else if signs[j] != Ordering::Equal && signs[i] != signs[j] {
            if (c[i].x, c[i].y) == (c[j].x, c[j].y) {
                crossings.push(At::Grid([c[i].x, c[i].y]));
            } else {
                crossings.push(At::Cross(Line::Cut(b.plane, plane_along(c[i], c[j]))));
            }
        }
    }
    // A convex face is crossed at exactly two points.
    let [p, q] = crossings[..] else { return None };
    let inside = super::along::Span::between(&carrier, p, q)?;
    let inside = (inside.from.1, inside.to.1);
    let extent: Vec<(At, At)> = parts
        .iter()
        .filter_map(|part| overlap(&carrier, inside, clip_to_convex(&carrier, part)?))
        .collect();
    (!extent.is_empty()).then(|| Meeting {
        faces: [flat.face.min(b.face), flat.face.max(b.face)],
        line,
        depth: b.plane,
        extent,
        edge_on: true,
    })
}

/// A support plane holding the 3D segment p-q (distinct on screen): through p, q and the grid
/// point beside p at p's depth, square to the segment on screen.
pub fn plane_along(p: GridPoint, q: GridPoint) -> Plane {
    let r = GridPoint {
        x: p.x - (q.y - p.y),
        y: p.y + (q.x - p.x),
        z: p.z,
    };
    Plane::through(p, q, r).expect("r is off the segment's line on screen")
}

/// The box of some grid points, one grid unit wider each way (a filter).
fn points_box(points: &[GridPoint]) -> [f64; 4] {
    let mut b = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for c in points {
        b = [
            b[0].min(c.x as f64),
            b[1].min(c.y as f64),
            b[2].max(c.x as f64),
            b[3].max(c.y as f64),
        ];
    }
    [b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0]
}

/// The polygon's screen box, one grid unit wider each way (a filter).
fn screen_box(screen: &ScreenScene, p: &ScreenPoly) -> [f64; 4] {
    points_box(screen.corners(p))
}

/// The depth range of the polygon's plane over its corners, widened by a grid unit and a
/// relative margin for the f64 evaluation (a filter).
fn depth_range(screen: &ScreenScene, p: &ScreenPoly) -> [f64; 2] {
    let pl = &p.plane;
    let (mut lo, mut hi) = (f64::MAX, f64::MIN);
    for c in screen.corners(p) {
        let z = -(pl.a as f64 * c.x as f64 + pl.b as f64 * c.y as f64 + pl.d as f64) / pl.c as f64;
        lo = lo.min(z);
        hi = hi.max(z);
    }
    let margin = 1.0 + 1e-9 * lo.abs().max(hi.abs());
    [lo - margin, hi + margin]
}

/// Does `line` pass strictly through the polygon: some corner on each side? Exact.
fn crosses(screen: &ScreenScene, p: &ScreenPoly, line: &Line) -> bool {
    let (mut pos, mut neg) = (false, false);
    for c in screen.corners(p) {
        match side_at(line, *c) {
            Ordering::Greater => pos = true,
            Ordering::Less => neg = true,
            Ordering::Equal => {}
        }
        if pos && neg {
            return true;
        }
    }
    false
}

/// The sign of `line` at a grid point, exactly.
fn side_at(line: &Line, c: GridPoint) -> Ordering {
    line.sign_at_grid(c.x, c.y).unwrap_or_else(|| {
        let [a, b, d] = line.exact();
        let (x, y): (bnum::types::I512, bnum::types::I512) =
            (bnum::cast::As::as_(c.x), bnum::cast::As::as_(c.y));
        (a * x + b * y + d).cmp(&bnum::cast::As::as_(0i32))
    })
}

/// The polygon's convex parts, each as its side lines with the inside positive.
fn convex_parts(screen: &ScreenScene, p: &ScreenPoly) -> Vec<Vec<Line>> {
    let corners = screen.corners(p);
    // Work counter-clockwise.
    let ccw: Vec<GridPoint> = if crate::exact::twice_signed_area(corners) > 0 {
        corners.to_vec()
    } else {
        corners.iter().rev().copied().collect()
    };
    let lines_of = |ring: &[GridPoint]| -> Vec<Line> {
        (0..ring.len())
            .filter_map(|i| Plane::edge(ring[i], ring[(i + 1) % ring.len()]).map(Line::Edge))
            .collect()
    };
    if ccw.len() == 3 {
        return vec![lines_of(&ccw)];
    }
    convex_piece_indices(&ccw)
        .iter()
        .map(|ring| lines_of(&ring.iter().map(|&i| ccw[i]).collect::<Vec<_>>()))
        .collect()
}

/// The common part of two spans of `carrier`, if it has length.
fn overlap(carrier: &Carrier, a: (At, At), b: (At, At)) -> Option<(At, At)> {
    let lo = if carrier.param(&a.0) >= carrier.param(&b.0) {
        a.0
    } else {
        b.0
    };
    let hi = if carrier.param(&a.1) <= carrier.param(&b.1) {
        a.1
    } else {
        b.1
    };
    (carrier.param(&lo) < carrier.param(&hi)).then_some((lo, hi))
}
