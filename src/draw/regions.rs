//! From visible pieces to drawable regions: the pieces of a group (one face, or one surface of
//! coplanar faces with the same paint) are united into regions with holes.
//!
//! Invariant: the regions of a group cover the union of its pieces, up to the output rounding of
//! their vertices (pixel coordinates rounded once, geo's union moving points by far less than a
//! millionth of a pixel), and each region lists the input faces whose pieces lie in it.

use crate::exact::Samples;
use crate::exact::polygon::Piece;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;
use crate::scene::{FaceId, Scene, newell_normal};
use crate::visibility::coverage::bounds;
use crate::visibility::grid::for_each_near;
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::BTreeMap;

/// One drawable region of a group.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Input face ids of the pieces in it, ascending, at least one.
    pub faces: Vec<FaceId>,
    /// Index of one of its pieces (whose face paints it).
    pub piece: usize,
    /// Outer ring, then holes; pixel coordinates, y down; even-odd.
    pub rings: Vec<Vec<[f64; 2]>>,
}

/// The regions of `pieces` (disjoint), grouped by `key`: groups in key order, and within a
/// group regions in the order of the union.
pub fn regions<K: Ord>(
    pieces: &[Piece],
    screen: &ScreenScene,
    key: impl Fn(&Piece) -> K,
) -> Vec<Region> {
    let vertices = shared_vertex_pixels(pieces, &Samples::new(screen.width, screen.height));
    regions_of(pieces, &vertices, screen, key, None)
}

/// [`regions`] of pieces whose [`shared_vertex_pixels`] are known, reporting stage "regions":
/// pieces merged of all.
pub fn regions_of<K: Ord>(
    pieces: &[Piece],
    vertices: &[Vec<[f64; 2]>],
    screen: &ScreenScene,
    key: impl Fn(&Piece) -> K,
    report: Option<Report>,
) -> Vec<Region> {
    let mut ticker = Ticker::new(report, "regions", pieces.len() as u64);
    let mut merged_pieces = 0;
    let s = Samples::new(screen.width, screen.height);
    let mut groups: BTreeMap<K, Vec<usize>> = BTreeMap::new();
    for (i, p) in pieces.iter().enumerate() {
        groups.entry(key(p)).or_default().push(i);
    }
    let face_of = |i: usize| screen.polys[pieces[i].poly as usize].id;
    let mut out = Vec::new();
    for members in groups.into_values() {
        // The pieces of the groups before this one are merged.
        ticker.tick(merged_pieces);
        merged_pieces += members.len() as u64;
        let group: Vec<&Piece> = members.iter().map(|&i| &pieces[i]).collect();
        let group_vertices: Vec<&[[f64; 2]]> =
            members.iter().map(|&i| vertices[i].as_slice()).collect();
        let mut faces: Vec<FaceId> = members.iter().map(|&i| face_of(i)).collect();
        faces.sort_unstable();
        faces.dedup();
        let merged = merge_rings(conforming_rings(&group, &group_vertices));
        if faces.len() == 1 || merged.len() == 1 {
            out.extend(merged.into_iter().map(|rings| Region {
                faces: faces.clone(),
                piece: members[0],
                rings,
            }));
            continue;
        }
        // Several faces in several regions: a piece belongs to the region that holds its
        // centroid (strictly inside a convex piece, so inside its region; f64, for labels only).
        for rings in merged {
            let inside: Vec<usize> = members
                .iter()
                .copied()
                .filter(|&i| ring_set_contains(&rings, centroid(&pieces[i], &s)))
                .collect();
            let mut region_faces: Vec<FaceId> = inside.iter().map(|&i| face_of(i)).collect();
            region_faces.sort_unstable();
            region_faces.dedup();
            let (faces, piece) = match inside.first() {
                Some(&first) => (region_faces, first),
                // Only slivers thinner than the rounding: label with the whole group.
                None => (faces.clone(), members[0]),
            };
            out.push(Region {
                faces,
                piece,
                rings,
            });
        }
    }
    ticker.finish();
    out
}

/// A surface label per screen polygon: polygons with equal `paint(index)` whose faces' world planes
/// fall in the same bucket share a label (numbered in polygon order). The bucket is the plane's
/// unit normal, turned towards the eye, and its offset, each rounded to 2^-20 (the offset of
/// the scene's size): coplanar faces share it, and near-coplanar ones almost always do, except
/// the rare pair that a rounding boundary separates, which then stays two paths.
/// This is a drawing choice outside the exactness contract: it never changes which face shows
/// where, only which abutting regions of the same paint share a path. It is not exact
/// coplanarity on purpose: CAD files written as decimals put the triangles of one flat face a
/// rounding error off each other's plane, and their seams would show.
pub fn surfaces<P: Ord>(
    scene: &Scene,
    screen: &ScreenScene,
    eye: DVec3,
    paint: impl Fn(usize) -> P,
) -> Vec<u32> {
    let size = scene
        .bounds()
        .map(|(lo, hi)| (hi - lo).length())
        .filter(|s| *s > 0.0)
        .unwrap_or(1.0);
    let q = |v: f64| (v * (1u64 << 20) as f64).round() as i64;
    let mut buckets: BTreeMap<(P, [i64; 4]), u32> = BTreeMap::new();
    let mut labels = Vec::with_capacity(screen.polys.len());
    let mut next = 0u32;
    for (index, poly) in screen.polys.iter().enumerate() {
        let face = &scene.faces[poly.face as usize];
        let corners = scene.face_corners(face);
        let p0 = scene.positions[corners[0] as usize];
        let mut n = newell_normal(corners.iter().map(|&i| scene.positions[i as usize])).normalize();
        // Opposite windings of one plane give opposite normals: turn both towards the eye.
        if n.dot(eye - p0) < 0.0 {
            n = -n;
        }
        let d = n.dot(p0) / size;
        let key = (paint(index), [q(n.x), q(n.y), q(n.z), q(d)]);
        let label = *buckets.entry(key).or_insert_with(|| {
            next += 1;
            next - 1
        });
        labels.push(label);
    }
    labels
}

/// The mean of a piece's vertices, in pixels.
fn centroid(p: &Piece, s: &Samples) -> [f64; 2] {
    let v = p.vertices_f64();
    let n = v.len() as f64;
    let [x, y] = v
        .iter()
        .fold([0.0, 0.0], |[x, y], [a, b]| [x + a / n, y + b / n]);
    [s.col_of(x), s.row_of(y)]
}

thread_local! {
    /// Set while a union runs whose panic is caught: the panic hook stays quiet then.
    static IN_UNION: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// `geo`'s unary union, or `None` if it panicked.
fn union_or_none(polys: &[geo::Polygon<f64>]) -> Option<geo::MultiPolygon<f64>> {
    static QUIET_HOOK: std::sync::Once = std::sync::Once::new();
    QUIET_HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !IN_UNION.with(|f| f.get()) {
                previous(info);
            }
        }));
    });
    IN_UNION.with(|f| f.set(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        geo::algorithm::bool_ops::unary_union(polys)
    }));
    IN_UNION.with(|f| f.set(false));
    result.ok()
}

/// Even-odd containment of a point in a ring set.
fn ring_set_contains(rings: &[Vec<[f64; 2]>], [px, py]: [f64; 2]) -> bool {
    let mut inside = false;
    for ring in rings {
        let n = ring.len();
        for k in 0..n {
            let ([x0, y0], [x1, y1]) = (ring[k], ring[(k + 1) % n]);
            if (y0 > py) != (y1 > py) && px < x0 + (py - y0) * (x1 - x0) / (y1 - y0) {
                inside = !inside;
            }
        }
    }
    inside
}

/// The outline of disjoint pieces (with their [`shared_vertex_pixels`]): the rings of their
/// union, outer rings and holes, even-odd. T-junctions are left to the union (no conforming
/// rings): where a union of drawing coordinates leaves a crack, it is far thinner than a pixel.
pub fn outline(pieces: &[Piece], vertices: &[Vec<[f64; 2]>]) -> Vec<Vec<[f64; 2]>> {
    debug_assert_eq!(pieces.len(), vertices.len());
    merge_rings(vertices.to_vec())
        .into_iter()
        .flatten()
        .collect()
}

/// Every piece's vertices in pixels, rounded once, with the same bits wherever pieces share an
/// exact vertex (decided exactly): the first piece having it gives its rounding to the others.
/// Two pieces' roundings of one point may otherwise differ in the last bits (each rounds its own
/// implicit vertex), and a union then leaves a crack between them.
pub fn shared_vertex_pixels(pieces: &[Piece], s: &Samples) -> Vec<Vec<[f64; 2]>> {
    let px = |[x, y]: [f64; 2]| [s.col_of(x), s.row_of(y)];
    let boxes: Vec<[f64; 4]> = pieces.iter().map(bounds).collect();
    let mut out: Vec<Vec<[f64; 2]>> = Vec::with_capacity(pieces.len());
    for_each_near(
        &boxes,
        |_| true,
        |a, near| {
            let pa = &pieces[a];
            let own = (0..pa.len())
                .map(|k| {
                    // Earlier pieces already hold the first rounding of every vertex they share.
                    near.iter()
                        .take_while(|&&b| b < a)
                        .find_map(|&b| {
                            (0..pieces[b].len())
                                .find(|&v| pa.same_vertex(k, &pieces[b], v))
                                .map(|v| out[b][v])
                        })
                        .unwrap_or_else(|| px(pa.vertex_f64(k)))
                })
                .collect();
            out.push(own);
        },
    );
    out
}

/// The pixel rings of one group's pieces (`vertices`: their [`shared_vertex_pixels`]), made
/// conforming: where a vertex of one piece lies on an edge of another (a T-junction, decided
/// exactly), it is inserted into that edge with the very same f64 coordinates, so shared
/// boundaries are identical segments and the union below closes them without slivers.
fn conforming_rings(pieces: &[&Piece], vertices: &[&[[f64; 2]]]) -> Vec<Vec<[f64; 2]>> {
    let boxes: Vec<[f64; 4]> = pieces.iter().map(|p| bounds(p)).collect();
    let mut rings = Vec::with_capacity(pieces.len());
    // The pieces whose bounds meet a piece's are the only ones with a vertex on its edges.
    for_each_near(
        &boxes,
        |_| true,
        |a, near| {
            let pa = pieces[a];
            let n = pa.len();
            let mut ring = Vec::with_capacity(n);
            for k in 0..n {
                let start = vertices[a][k];
                ring.push(start);
                // Vertices of other pieces strictly inside edge k (line k, between vertices k
                // and k+1): on line k, strictly inside every other line.
                let (edge, edge_approx) = (&pa.lines[k], &pa.line_approx[k]);
                let mut on_edge: Vec<(f64, [f64; 2])> = Vec::new();
                for &b in near {
                    let pb = pieces[b];
                    for (v, &q) in vertices[b].iter().enumerate() {
                        if pb.vertex_line_sign_with(v, edge, edge_approx) != Ordering::Equal {
                            continue;
                        }
                        let inside = (pa.lines.iter().zip(&pa.line_approx)).enumerate().all(
                            |(j, (l, la))| {
                                j == k || pb.vertex_line_sign_with(v, l, la) == Ordering::Greater
                            },
                        );
                        if inside {
                            let t = (q[0] - start[0]).abs() + (q[1] - start[1]).abs();
                            on_edge.push((t, q));
                        }
                    }
                }
                on_edge.sort_by(|x, y| x.0.total_cmp(&y.0));
                on_edge.dedup_by(|x, y| x.1 == y.1);
                ring.extend(on_edge.into_iter().map(|(_, q)| q));
            }
            rings.push(ring);
        },
    );
    rings
}

/// The union of one group's disjoint convex rings (pixel coordinates) as regions, each an outer
/// ring followed by its holes. geo's boolean union works in f64 on coordinates already rounded for
/// output, and its snapping moves a point by far less than a millionth of a pixel: within the
/// output-rounding approximation. A single ring is returned as it is.
fn merge_rings(rings: Vec<Vec<[f64; 2]>>) -> Vec<Vec<Vec<[f64; 2]>>> {
    use geo::{LineString, Polygon};
    if rings.len() == 1 {
        return vec![rings];
    }
    let polys: Vec<Polygon<f64>> = rings
        .into_iter()
        .map(|r| {
            Polygon::new(
                LineString::from(r.into_iter().map(|[x, y]| (x, y)).collect::<Vec<_>>()),
                vec![],
            )
        })
        .collect();
    // geo's union (i_overlay) can panic on some inputs (an index overflow in its solver, met on
    // slivers): then the group is drawn as its conforming rings, unmerged, which covers the
    // same area. The panic is expected there, so it is not reported on stderr.
    let Some(merged) = union_or_none(&polys) else {
        return polys
            .into_iter()
            .map(|p| {
                let mut ring: Vec<[f64; 2]> = p.exterior().coords().map(|c| [c.x, c.y]).collect();
                if ring.len() > 1 && ring.first() == ring.last() {
                    ring.pop();
                }
                vec![ring]
            })
            .collect();
    };
    let open = |ls: &LineString<f64>| -> Vec<[f64; 2]> {
        let mut v: Vec<[f64; 2]> = ls.coords().map(|c| [c.x, c.y]).collect();
        // geo closes rings by repeating the first point; drawings do not.
        if v.len() > 1 && v.first() == v.last() {
            v.pop();
        }
        v
    };
    merged
        .0
        .iter()
        .map(|poly| {
            std::iter::once(open(poly.exterior()))
                .chain(poly.interiors().iter().map(open))
                .collect()
        })
        .collect()
}
