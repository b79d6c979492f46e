//! Sides matched by their two grid points: the first step of finding a contour (the sides that
//! do not cancel) for the occlusion cells and the clear pieces alike.
//!
//! A mesh's vertex is one grid point whichever faces name it (`ScreenScene::grid_points`), so
//! the sides of abutting faces name the same two points. Sorted by their lower point into
//! buckets ([`sorted_by_low`]: no comparison of all the sides, no coordinates read), a bucket's
//! sides meet their partners by the other point. Invariant: a pair of points is reported with exactly the
//! numbers of sides that run each way between them; only the pairs the caller keeps are listed.

use crate::buckets::sorted_by_low;
use rayon::prelude::*;

/// A side from grid point `from` to grid point `to` (indices, distinct, below 2^31), packed as
/// the pair's lower point, upper point and whether it runs upwards: the key [`point_pairs`]
/// reads.
pub(crate) fn side_key(from: u32, to: u32) -> u64 {
    debug_assert!(from != to && from.max(to) < 1 << 31);
    let (lo, hi, up) = if from < to {
        (from, to, 1)
    } else {
        (to, from, 0)
    };
    (lo as u64) << 33 | (hi as u64) << 1 | up
}

/// One pair of grid points that sides run between.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct PointPair {
    /// The lower point's index.
    pub lo: u32,
    /// The upper point's index.
    pub hi: u32,
    /// Sides from `lo` to `hi`.
    pub up: u32,
    /// Sides from `hi` to `lo`.
    pub down: u32,
}

/// The pairs of points that the sides `keys` ([`side_key`]s of points below `points`) run
/// between, with how many run each way, those `keep(up, down)` keeps: ordered by lower point,
/// then upper.
pub(crate) fn point_pairs(
    points: usize,
    keys: &[u64],
    keep: impl Fn(u32, u32) -> bool + Sync,
) -> Vec<PointPair> {
    assert!(points < 1 << 31, "grid points are numbered in 31 bits");
    // A key orders by its lower point first: sorted, the sides of one pair are neighbours.
    let sorted = sorted_by_low(points, || keys.iter().copied(), |&key| (key >> 33) as u32);
    (sorted.par_chunk_by(|a, b| a >> 1 == b >> 1))
        .filter_map(|run| {
            let up = run.iter().filter(|&&s| s & 1 == 1).count() as u32;
            let down = run.len() as u32 - up;
            let (lo, hi) = ((run[0] >> 33) as u32, (run[0] >> 1) as u32);
            keep(up, down).then_some(PointPair { lo, hi, up, down })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Each pair of points is listed once with its sides counted each way, as a sort of all
        /// the sides by their points counts them, and only when `keep` keeps it.
        #[test]
        fn pairs_count_the_sides_as_a_sort_of_all_sides_does(
            sides in prop::collection::vec((0u32..12, 0u32..12), 0..60),
        ) {
            let keys: Vec<u64> =
                sides.iter().filter(|(a, b)| a != b).map(|&(a, b)| side_key(a, b)).collect();
            let mut want: Vec<PointPair> = Vec::new();
            let mut sorted = keys.clone();
            sorted.sort_unstable();
            for run in sorted.chunk_by(|a, b| a >> 1 == b >> 1) {
                let up = run.iter().filter(|&&k| k & 1 == 1).count() as u32;
                let (lo, hi) = ((run[0] >> 33) as u32, (run[0] >> 1) as u32);
                let pair = PointPair { lo, hi, up, down: run.len() as u32 - up };
                if up != pair.down {
                    want.push(pair);
                }
            }
            prop_assert_eq!(point_pairs(12, &keys, |up, down| up != down), want);
            prop_assert_eq!(point_pairs(12, &keys, |_, _| true).len(),
                sorted.chunk_by(|a, b| a >> 1 == b >> 1).count());
        }
    }
}
