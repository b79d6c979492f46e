//! A counting sort for items keyed first by a small dense number (a vertex id, a grid point's
//! index): pairs of ends gathered by their lower end, where a comparison sort of all of them
//! took several times as long. Used for the edges the drawing pairs, the face sides the line
//! features pair, and the sides the occlusion cells and clear pieces match.
//!
//! Invariant: the result is exactly the items' sorted order (`Ord`), given that the order
//! compares the low key first.

/// `items()` sorted, where `low(item)` is below `lows` and the items' `Ord` compares it first:
/// placed into one bucket per low key by a counting sort (`items` is called twice: counted,
/// then placed), then each bucket's few items sorted.
pub(crate) fn sorted_by_low<T, I>(
    lows: usize,
    items: impl Fn() -> I,
    low: impl Fn(&T) -> u32,
) -> Vec<T>
where
    T: Ord + Copy + Default,
    I: Iterator<Item = T>,
{
    let mut start = vec![0usize; lows + 1];
    for t in items() {
        start[low(&t) as usize + 1] += 1;
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    let mut sorted = vec![T::default(); start[lows]];
    let mut next = start.clone();
    for t in items() {
        let at = &mut next[low(&t) as usize];
        sorted[*at] = t;
        *at += 1;
    }
    drop(next);
    for ends in start.windows(2) {
        sorted[ends[0]..ends[1]].sort_unstable();
    }
    sorted
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The buckets give the order of one sort of all the items.
        #[test]
        fn items_come_sorted_as_one_sort_sorts_them(
            items in prop::collection::vec((0u32..20, 0u32..20, any::<bool>()), 0..80),
        ) {
            let mut want = items.clone();
            want.sort_unstable();
            prop_assert_eq!(sorted_by_low(20, || items.iter().copied(), |t| t.0), want);
        }
    }
}
