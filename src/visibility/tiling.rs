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
use crate::exact::predicates::orient2d;
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
    let turn = crate::exact::twice_signed_area(screen.corners(&screen.polys[first as usize]));
    if turn == Ordering::Equal {
        return false;
    }
    // Directed edges (x0, y0, x1, y1) of every polygon; an edge met again the same way is a
    // fold or a duplicate.
    let mut edges: FxHashSet<[i64; 4]> = FxHashSet::default();
    edges.reserve(polys.len() * 3);
    for &k in polys {
        let c = screen.corners(&screen.polys[k as usize]);
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
