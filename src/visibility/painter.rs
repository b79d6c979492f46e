//! The painter's algorithm as matplotlib's mplot3d and GL2PS's simple sort do it: whole faces,
//! never split, sorted back to front by their farthest corner and drawn in that order.
//!
//! **Approximate**, and here to be measured against: it is wrong wherever the farthest-corner
//! order is not the occlusion order, which it cannot be for cyclic overlaps and interpenetrating
//! faces, and need not be even without them (a long face reaching far back sorts behind a small
//! face it covers).
//!
//! Invariant: one fragment per screen polygon (drawn as the polygon's exact pixel ring), in an
//! order fixed by the input alone: farthest corner depth (largest grid z) first; ties by nearest
//! corner depth, farthest first; then by face id, smaller first (as the z-buffer's tie rule lets
//! the larger id win); then by polygon index. The order never flickers between runs.

use super::Strategy;
use super::visible_set::{Fragment, Stats, VisibleSet};
use crate::progress::Report;
use crate::project::ScreenScene;
use std::cmp::Reverse;

/// Depth-sort painter (approximate baseline): every polygon a [`Fragment::Polygon`], layered in
/// [`painter_order`], translucent or not.
#[derive(Clone, Copy, Debug, Default)]
pub struct Painter;

impl Strategy for Painter {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        _translucent: &dyn Fn(u32) -> bool,
        _report: Option<Report>,
    ) -> VisibleSet {
        let layered: Vec<Fragment> = painter_order(screen)
            .into_iter()
            .map(|k| Fragment::Polygon(k as u32))
            .collect();
        let mut stats = Stats::new();
        stats.insert("faces_drawn".into(), layered.len().into());
        VisibleSet {
            pieces: Vec::new(),
            layered,
            stats,
        }
    }
}

/// Indices into `screen.polys`, back to front (see the module docs for the key).
pub fn painter_order(screen: &ScreenScene) -> Vec<usize> {
    let mut keys: Vec<(Reverse<i64>, Reverse<i64>, u32, usize)> = screen
        .polys
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let pts = screen.corners(p);
            let far = pts.iter().map(|q| q.z).max().unwrap_or(0);
            let near = pts.iter().map(|q| q.z).min().unwrap_or(0);
            (Reverse(far), Reverse(near), p.id, k)
        })
        .collect();
    // Every key is distinct (the index is last), so an unstable sort is deterministic.
    keys.sort_unstable();
    keys.into_iter().map(|k| k.3).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{GridPoint, Plane};
    use crate::project::ScreenPoly;

    fn screen_of(tris: &[([i64; 3], u32)]) -> ScreenScene {
        let mut s = ScreenScene {
            width: 8,
            height: 8,
            ..ScreenScene::default()
        };
        for (k, (zs, id)) in tris.iter().enumerate() {
            let pts = [(0, 0), (1 << 20, 0), (0, 1 << 20)]
                .iter()
                .zip(zs)
                .map(|(&(x, y), &z)| GridPoint { x, y, z })
                .collect::<Vec<_>>();
            Plane::of_polygon(&pts).unwrap();
            let start = s.push_corners(&pts);
            s.polys.push(ScreenPoly {
                face: k as u32,
                id: *id,
                mesh: 0,
                start,
                len: 3,
                front: true,
            });
        }
        s
    }

    #[test]
    fn farthest_corner_first_then_nearest_then_id_then_index() {
        let s = screen_of(&[
            ([0, 0, 10], 5),   // far 10, near 0
            ([0, 0, 20], 9),   // far 20: first
            ([5, 5, 10], 1),   // far 10, near 5: before the first one
            ([5, 10, 5], 0),   // same depths as the previous, smaller id: before it
            ([5, 10, 5], 0),   // same key again: by index
            ([-9, -9, -9], 3), // nearest: last
        ]);
        assert_eq!(painter_order(&s), vec![1, 3, 4, 2, 0, 5]);
    }
}
