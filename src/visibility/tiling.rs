//! Do some screen polygons cover one convex region exactly once? Then no two of them overlap,
//! and none needs ordering: the test that lets `auto` skip the depth work for a convex mesh
//! (and for any mesh seen so that its faces do not overlap).
//!
//! The argument, exact on the grid: give every polygon its boundary as directed edges. When all
//! polygons turn the same way on screen, the number of them covering a point (off their edges)
//! is the winding number of the sum of their boundaries around it, up to that common sign.
//! Edges shared by two polygons and run in opposite directions cancel in the sum; what is left is
//! the outline. If the outline is one closed loop that only turns one way and turns once, it is
//! a convex simple polygon: winding 1 inside, 0 outside, so every point inside is covered by
//! exactly one polygon. Every test is on integer grid points (exact matching of edge ends,
//! orientation signs in i128); anything else (a T-junction, a hole left by a face dropped after
//! snapping, two loops, a fold) fails the test and the caller falls back to ordering.

use crate::exact::GridPoint;
use crate::exact::predicates::{cross_xy, orient2d};
use crate::project::ScreenScene;
use rustc_hash::FxHashMap;
use rustc_hash::FxHashSet;
use std::cmp::Ordering;

/// Do `polys` (indices into `screen.polys`) cover one convex region exactly once? See the
/// module docs; `false` whenever that is not proven.
pub fn tiles_convex_region_once(screen: &ScreenScene, polys: &[u32]) -> bool {
    let Some(&first) = polys.first() else {
        return true;
    };
    let turn = crate::exact::twice_signed_area(&screen.corners(&screen.polys[first as usize]));
    if turn == Ordering::Equal {
        return false;
    }
    // Directed edges (x0, y0, x1, y1) of every polygon; an edge met again the same way is a
    // fold or a duplicate.
    let mut edges: FxHashSet<[i64; 4]> = FxHashSet::default();
    edges.reserve(polys.len() * 3);
    for &k in polys {
        let c = &screen.corners(&screen.polys[k as usize]);
        if crate::exact::twice_signed_area(c) != turn {
            return false;
        }
        for i in 0..c.len() {
            let (p, q) = (c[i], c[(i + 1) % c.len()]);
            if !edges.insert([p.x, p.y, q.x, q.y]) {
                return false;
            }
        }
    }
    // The outline: edges whose reverse no polygon has, as next-edge links.
    let mut next: FxHashMap<[i64; 2], [i64; 2]> = FxHashMap::default();
    for e in &edges {
        if !edges.contains(&[e[2], e[3], e[0], e[1]])
            && next.insert([e[0], e[1]], [e[2], e[3]]).is_some()
        {
            // Two outline edges leave one point: not a single simple loop.
            return false;
        }
    }
    let Some((&start, _)) = next.iter().min() else {
        return false;
    };
    let mut loop_points: Vec<[i64; 2]> = vec![start];
    let mut at = start;
    loop {
        at = match next.get(&at) {
            Some(&n) => n,
            None => return false,
        };
        if at == start {
            break;
        }
        if loop_points.len() >= next.len() {
            return false;
        }
        loop_points.push(at);
    }
    // One loop through every outline edge, turning one way, once.
    loop_points.len() == next.len() && convex_once(&loop_points, turn)
}

/// Twice the area of the convex hull of `polys`' corners (indices into `screen.polys`): exact
/// on the grid (Andrew's monotone chain, orientations in i128). Polygons that cover a convex
/// region once add up to it.
pub fn twice_hull_area(screen: &ScreenScene, polys: &[u32]) -> i128 {
    let mut ids: Vec<u32> = polys
        .iter()
        .flat_map(|&k| {
            screen
                .corner_indices(&screen.polys[k as usize])
                .iter()
                .copied()
        })
        .collect();
    ids.sort_unstable();
    ids.dedup();
    let mut points: Vec<[i64; 2]> = ids
        .iter()
        .map(|&i| {
            let g = screen.grid_points[i as usize];
            [g.x, g.y]
        })
        .collect();
    points.sort_unstable();
    points.dedup();
    if points.len() < 3 {
        return 0;
    }
    // Lower hull left to right, then upper hull right to left: counter-clockwise. A point
    // that does not turn left is dropped (collinear ones too).
    let mut hull: Vec<[i64; 2]> = Vec::with_capacity(points.len() + 1);
    let add = |hull: &mut Vec<[i64; 2]>, p: [i64; 2], floor: usize| {
        while hull.len() >= floor && cross_xy(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0 {
            hull.pop();
        }
        hull.push(p);
    };
    for &p in &points {
        add(&mut hull, p, 2);
    }
    let lower = hull.len();
    for &p in points.iter().rev().skip(1) {
        add(&mut hull, p, lower + 1);
    }
    hull.pop();
    twice_ring_area(&hull)
}

/// Twice the signed area of a closed ring of grid (x, y) points (the shoelace sum), exact:
/// positive when it runs counter-clockwise.
pub fn twice_ring_area(ring: &[[i64; 2]]) -> i128 {
    (0..ring.len())
        .map(|i| {
            let (c, d) = (ring[i], ring[(i + 1) % ring.len()]);
            c[0] as i128 * d[1] as i128 - d[0] as i128 * c[1] as i128
        })
        .sum()
}

/// Does the closed loop turn only the way `turn` says (straight on allowed, never back) and go
/// round exactly once?
fn convex_once(points: &[[i64; 2]], turn: Ordering) -> bool {
    let n = points.len();
    if n < 3 {
        return false;
    }
    let gp = |[x, y]: [i64; 2]| GridPoint { x, y, z: 0 };
    // Mirror a clockwise loop so that the test is for counter-clockwise turns.
    let flip = |v: i64| if turn == Ordering::Less { -v } else { v };
    // Which half of the circle a direction points into: [0, pi) or [pi, 2 pi).
    let half = |dx: i64, dy: i64| {
        let dy = flip(dy);
        !(dy > 0 || (dy == 0 && dx > 0))
    };
    let mut wraps = 0;
    for i in 0..n {
        let (a, b, c) = (points[i], points[(i + 1) % n], points[(i + 2) % n]);
        match orient2d(gp(a), gp(b), gp(c)) {
            o if o == turn => {}
            Ordering::Equal => {
                // Straight on, not back: the two edges point the same way.
                let dot = (b[0] - a[0]) as i128 * (c[0] - b[0]) as i128
                    + (b[1] - a[1]) as i128 * (c[1] - b[1]) as i128;
                if dot <= 0 {
                    return false;
                }
            }
            _ => return false,
        }
        let (d0, d1) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
        if half(d0[0], d0[1]) && !half(d1[0], d1[1]) {
            wraps += 1;
        }
    }
    wraps == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A screen scene of polygons given as (x, y) rings in the plane z = 0, all in mesh 0.
    fn screen_of(rings: &[&[[i64; 2]]]) -> ScreenScene {
        crate::visibility::screen_of_polygons(rings.iter().map(|ring| {
            (ring.iter())
                .map(|&[x, y]| GridPoint { x, y, z: 0 })
                .collect()
        }))
    }

    fn tiles(rings: &[&[[i64; 2]]]) -> bool {
        let s = screen_of(rings);
        let all: Vec<u32> = (0..s.polys.len() as u32).collect();
        tiles_convex_region_once(&s, &all)
    }

    #[test]
    fn a_fan_around_a_centre_tiles_its_convex_outline_once() {
        let (c, r) = ([0, 0], [[4, 0], [0, 4], [-4, 0], [0, -4]]);
        let fan: Vec<[[i64; 2]; 3]> = (0..4).map(|i| [c, r[i], r[(i + 1) % 4]]).collect();
        let rings: Vec<&[[i64; 2]]> = fan.iter().map(|t| &t[..]).collect();
        assert!(tiles(&rings));
        // Clockwise everywhere (an inside-out mesh's front faces): the same, mirrored.
        let cw: Vec<[[i64; 2]; 3]> = fan.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let rings: Vec<&[[i64; 2]]> = cw.iter().map(|t| &t[..]).collect();
        assert!(tiles(&rings));
        // A straight run along the outline (a T-free midpoint on a side) is fine.
        assert!(tiles(&[
            &[[0, 0], [2, 0], [4, 0], [4, 4]],
            &[[0, 0], [4, 4], [0, 4]]
        ]));
    }

    #[test]
    fn overlaps_folds_holes_and_concave_outlines_are_not_proven() {
        // Two triangles overlapping, sharing no edge.
        assert!(!tiles(&[
            &[[0, 0], [4, 0], [0, 4]],
            &[[1, 1], [5, 1], [1, 5]]
        ]));
        // A fold: the second triangle turned over onto the first across their shared edge.
        assert!(!tiles(&[
            &[[0, 0], [4, 0], [0, 4]],
            &[[0, 0], [0, 4], [1, 1]]
        ]));
        // An L of three squares: no overlap, but the outline is not convex.
        assert!(!tiles(&[
            &[[0, 0], [2, 0], [2, 2], [0, 2]],
            &[[2, 0], [4, 0], [4, 2], [2, 2]],
            &[[0, 2], [2, 2], [2, 4], [0, 4]],
        ]));
        // A square ring of four trapezoids around a hole: two outline loops.
        let (o, i) = (
            [[0, 0], [6, 0], [6, 6], [0, 6]],
            [[2, 2], [4, 2], [4, 4], [2, 4]],
        );
        let ring: Vec<[[i64; 2]; 4]> = (0..4)
            .map(|k| [o[k], o[(k + 1) % 4], i[(k + 1) % 4], i[k]])
            .collect();
        let rings: Vec<&[[i64; 2]]> = ring.iter().map(|q| &q[..]).collect();
        assert!(!tiles(&rings));
        // A T-junction: two triangles meet at the midpoint of the third's long side. The square
        // is covered once, but the long side matches no edge exactly: refused (conservative).
        assert!(!tiles(&[
            &[[0, 0], [4, 0], [0, 4]],
            &[[4, 0], [4, 4], [2, 2]],
            &[[2, 2], [4, 4], [0, 4]],
        ]));
        // The same square with the matching edges tiles once.
        assert!(tiles(&[
            &[[0, 0], [4, 0], [2, 2]],
            &[[0, 0], [2, 2], [0, 4]],
            &[[2, 2], [4, 0], [4, 4], [0, 4]],
        ]));
        // A polygon wound the other way from the rest.
        assert!(!tiles(&[
            &[[0, 0], [4, 0], [0, 4]],
            &[[4, 0], [0, 4], [4, 4]]
        ]));
    }

    #[test]
    fn an_outline_that_goes_round_twice_is_refused() {
        // A fan from the centre to the corners of the star heptagon {7/2}: every triangle turns
        // left, every spoke cancels, and the outline turns left at each of its seven corners,
        // but it goes round twice (each point inside the inner heptagon is covered twice).
        let corner = |k: usize| {
            let a = std::f64::consts::TAU * (2 * k % 7) as f64 / 7.0;
            [
                (1000.0 * a.cos()).round() as i64,
                (1000.0 * a.sin()).round() as i64,
            ]
        };
        let fan: Vec<[[i64; 2]; 3]> = (0..7).map(|k| [[0, 0], corner(k), corner(k + 1)]).collect();
        let rings: Vec<&[[i64; 2]]> = fan.iter().map(|t| &t[..]).collect();
        assert!(!tiles(&rings));
        // The plain heptagon's fan (step 1) tiles once.
        let corner1 = |k: usize| {
            let a = std::f64::consts::TAU * (k % 7) as f64 / 7.0;
            [
                (1000.0 * a.cos()).round() as i64,
                (1000.0 * a.sin()).round() as i64,
            ]
        };
        let fan: Vec<[[i64; 2]; 3]> = (0..7)
            .map(|k| [[0, 0], corner1(k), corner1(k + 1)])
            .collect();
        let rings: Vec<&[[i64; 2]]> = fan.iter().map(|t| &t[..]).collect();
        assert!(tiles(&rings));
    }

    /// The hull's area is the convex region's, whatever points lie inside or along its sides,
    /// and more than an L-shaped region's.
    #[test]
    fn the_hull_area_is_the_convex_outlines() {
        // A 4 x 4 square as five triangles around its centre (its lower side cut at (2, 0)).
        let square = screen_of(&[
            &[[0, 0], [2, 0], [2, 2]],
            &[[2, 0], [4, 0], [2, 2]],
            &[[4, 0], [4, 4], [2, 2]],
            &[[4, 4], [0, 4], [2, 2]],
            &[[0, 4], [0, 0], [2, 2]],
        ]);
        assert_eq!(twice_hull_area(&square, &[0, 1, 2, 3, 4]), 32);
        assert_eq!(twice_hull_area(&square, &[0]), 4);
        // An L of three unit squares: its hull is the 2 x 2 square less half a unit square.
        let l = screen_of(&[
            &[[0, 0], [1, 0], [1, 1], [0, 1]],
            &[[1, 0], [2, 0], [2, 1], [1, 1]],
            &[[0, 1], [1, 1], [1, 2], [0, 2]],
        ]);
        assert_eq!(twice_hull_area(&l, &[0, 1, 2]), 7);
    }
}
