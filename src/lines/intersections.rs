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
    // Convex parts, made when a pair first needs them.
    let mut parts: Vec<Option<Vec<Vec<Line>>>> = vec![None; polys.len()];
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
    let boxes: Vec<[f64; 6]> = boxes
        .iter()
        .zip(&depths)
        .map(|(b, d)| [b[0], b[1], d[0], b[2], b[3], d[1]])
        .collect();
    let mut on_pair = |a: usize, b: usize| {
        if a >= n && b >= n {
            return;
        }
        if b >= n {
            // An edge-on face and a polygon.
            let flat = &flats[b - n];
            if !share_an_edge(&welded(flat.face), &welded(polys[a].face)) {
                let parts_a = parts[a].get_or_insert_with(|| convex_parts(screen, &polys[a]));
                out.extend(edge_on_meeting(flat, &polys[a], parts_a));
            }
            return;
        }
        let (pa, pb) = (&polys[a], &polys[b]);
        let line = Line::Cut(pa.plane, pb.plane);
        // For a face lying in its plane, the meeting line's side at a corner is the side of
        // the other plane the corner lies on (cheaper to evaluate).
        let straddles = |p: &ScreenPoly, planar: bool, other: &Plane| {
            if planar {
                straddles_plane(screen, p, other)
            } else {
                crosses(screen, p, &line)
            }
        };
        if !straddles(pb, planar[b], &pa.plane) || !straddles(pa, planar[a], &pb.plane) {
            return;
        }
        match shared(&welded(pa.face), &welded(pb.face)) {
            0 => {}
            1 if planar[a] && planar[b] => {
                if apart_beyond_corner(screen, pa, pb, &line) == Some(true) {
                    return;
                }
            }
            _ => return,
        }
        let carrier = Carrier::new(line);
        let mut extent = Vec::new();
        parts[a].get_or_insert_with(|| convex_parts(screen, pa));
        parts[b].get_or_insert_with(|| convex_parts(screen, pb));
        let (parts_a, parts_b) = (parts[a].as_ref().unwrap(), parts[b].as_ref().unwrap());
        for part_a in parts_a {
            let Some(ia) = clip_to_convex(&carrier, part_a) else {
                continue;
            };
            for part_b in parts_b {
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
    };
    for (a, b) in overlapping_pairs(&boxes) {
        on_pair(a, b);
    }
    out
}

/// Every two boxes (a < b) of `boxes` (x0, y0, z0, x1, y1, z1) whose closed extents meet (a
/// filter: the caller decides exactly). A 3D grid of about `boxes.len()` cells whose slabs
/// along each axis hold about equal numbers of box centres (so that perspective depth, crowded
/// near the far plane, is cut as finely as anything else); a pair is reported in the one cell
/// holding the corner where both boxes start. Order: by cell, then by box.
fn overlapping_pairs(boxes: &[[f64; 6]]) -> Vec<(usize, usize)> {
    if boxes.len() < 2 {
        return Vec::new();
    }
    let per_axis = ((boxes.len() as f64).cbrt().ceil() as usize).clamp(1, 96);
    // Slab boundaries per axis: quantiles of the box centres.
    let bounds: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            let mut c: Vec<f64> = boxes.iter().map(|b| 0.5 * (b[k] + b[k + 3])).collect();
            c.sort_unstable_by(f64::total_cmp);
            (1..per_axis).map(|s| c[s * c.len() / per_axis]).collect()
        })
        .collect();
    // The slab of a value: how many boundaries lie at or below it.
    let slab = |v: f64, k: usize| bounds[k].partition_point(|&b| b <= v);
    let ranges: Vec<[usize; 6]> = boxes
        .iter()
        .map(|b| std::array::from_fn(|i| slab(b[i], i % 3)))
        .collect();
    let index = |x: usize, y: usize, z: usize| (z * per_axis + y) * per_axis + x;
    let mut cells: Vec<Vec<u32>> = vec![Vec::new(); per_axis * per_axis * per_axis];
    for (i, r) in ranges.iter().enumerate() {
        for z in r[2]..=r[5] {
            for y in r[1]..=r[4] {
                for x in r[0]..=r[3] {
                    cells[index(x, y, z)].push(i as u32);
                }
            }
        }
    }
    let mut pairs = Vec::new();
    for (c, cell) in cells.iter().enumerate() {
        for (k, &a) in cell.iter().enumerate() {
            let (ba, ra) = (&boxes[a as usize], &ranges[a as usize]);
            for &b in &cell[k + 1..] {
                let (bb, rb) = (&boxes[b as usize], &ranges[b as usize]);
                if (0..3).any(|i| ba[i] > bb[i + 3] || bb[i] > ba[i + 3]) {
                    continue;
                }
                if index(ra[0].max(rb[0]), ra[1].max(rb[1]), ra[2].max(rb[2])) == c {
                    pairs.push((a as usize, b as usize));
                }
            }
        }
    }
    pairs
}

/// For two triangles with a common corner V that the meeting line of their planes passes
/// through: do they go apart from V (each meets the line on a different side of V, so they do
/// not cross beyond it)? Exact, on grid integers; `None` when they are not two triangles with
/// a common corner. Seen from V, the line runs into a triangle (V, p, q) on the side where the
/// segment p-q crosses it: with p on the line's positive side, that is along the line's
/// direction exactly when the triangle turns clockwise.
fn apart_beyond_corner(
    screen: &ScreenScene,
    pa: &ScreenPoly,
    pb: &ScreenPoly,
    line: &Line,
) -> Option<bool> {
    let (ca, cb) = (screen.corners(pa), screen.corners(pb));
    if ca.len() != 3 || cb.len() != 3 {
        return None;
    }
    let (i, j) = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .find(|&(i, j)| ca[i] == cb[j])?;
    let direction = |c: &[GridPoint], k: usize| -> Option<i32> {
        let (v, p, q) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
        let turn = crate::exact::predicates::orient2d(v, p, q);
        match (side_at(line, p), turn) {
            (Ordering::Equal, _) | (_, Ordering::Equal) => None,
            (sp, turn) => Some(if (sp == Ordering::Greater) == (turn == Ordering::Less) {
                1
            } else {
                -1
            }),
        }
    };
    Some(direction(ca, i)? != direction(cb, j)?)
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

/// Do the polygon's corners lie strictly on both sides of `plane`? Exact.
fn straddles_plane(screen: &ScreenScene, p: &ScreenPoly, plane: &Plane) -> bool {
    let (mut pos, mut neg) = (false, false);
    for c in screen.corners(p) {
        let v = plane.value_at(*c);
        pos |= v > 0;
        neg |= v < 0;
    }
    pos && neg
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
pub(crate) fn convex_parts(screen: &ScreenScene, p: &ScreenPoly) -> Vec<Vec<Line>> {
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
pub(crate) fn overlap(carrier: &Carrier, a: (At, At), b: (At, At)) -> Option<(At, At)> {
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
