//! Newell, Newell and Sancha's depth sort (`newell`): a back-to-front list of convex pieces in
//! which no piece hides any piece after it, then the visible set by exact overpainting along
//! that list.
//!
//! The sort (the course notes, section 6.1): pieces in order of their farthest depth; the head
//! P of the list is compared with every piece Q whose depth extent overlaps P's, by tests in
//! increasing cost, any of which proves that painting P first is right:
//! 1. the depth extents do not overlap (P wholly farther than Q);
//! 2. the screen boxes do not overlap;
//! 3. P lies wholly behind Q's plane;
//! 4. Q lies wholly in front of P's plane;
//! 5. the projections do not overlap (exactly: [`separated`]).
//!
//! When all fail for some Q, Q moves to the head if the reversed tests 3 or 4 prove Q may go
//! first; otherwise the two pass through each other and P is cut by Q's plane (P then
//! straddles it: both orders failing means each has points on both sides of the other's plane).
//! A piece that would move a second time before anything is painted closes a cycle of the list:
//! then some piece of the cycle straddles the plane of another (were none to, a BSP of the
//! cycle's pieces would order them without a cut, and a cycle has no order), and it is cut. A
//! cut part never straddles the same plane again, so cuts are finitely many and the sort ends.
//!
//! Invariant of the list: wherever two pieces overlap on screen, the later one is nearer (for
//! coplanar faces, the later one wins the z-buffer's tie: larger face id, then later polygon).
//! Tests 1 and 2 use bounds proven to contain the pieces ([`depth::range`], [`Piece::bounds`]):
//! they only ever skip a pair that certainly passes; 3, 4 and 5 are exact.
//!
//! The visible set is the list painted exactly, back to front ([`Canvas`]): each opaque piece,
//! as it is painted, removes what it covers from the pieces painted before it. This is
//! independent of the coverage map (no depth is compared while painting): a wrong order would
//! show, and the conformance tests compare the two. Translucent pieces are layered in the order
//! of the list, less what later opaque pieces cover.

use super::coverage::{subtract, subtract_all, tie_key};
use super::depth;
use super::live::{Live, bounds, overlap};
use super::visible_set::{Fragment, Stats, VisibleSet, put_counts};
use super::{Strategy, initial_pieces, separated_on};
use crate::exact::polygon::{Piece, Split, separated};
use crate::exact::predicates::fallback_count;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;

/// Newell's depth sort. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Newell;

/// Counters of one depth sort.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct NewellStats {
    /// Pieces handed in.
    pub pieces: usize,
    /// Pairs whose depth extents may overlap, put through tests 2 to 5.
    pub compared: usize,
    /// Pairs each of tests 2, 3, 4 and 5 settled.
    pub settled_by: [usize; 4],
    /// Pieces moved to the head of the list.
    pub moves: usize,
    /// Cuts of a piece passing through the head piece (both orders failed).
    pub interpenetration_cuts: usize,
    /// Cuts that broke a cycle of the list.
    pub cycle_cuts: usize,
    /// Length of the final back-to-front list.
    pub list: usize,
}

impl Strategy for Newell {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        let fallbacks = fallback_count();
        let (order, st) = depth_order(screen, initial_pieces(screen), report);
        let (pieces, layered) = overpaint(&order, translucent);
        let mut stats = Stats::new();
        put_counts(
            &mut stats,
            [
                ("pieces", st.pieces),
                ("compared", st.compared),
                ("settled_by_screen_box", st.settled_by[0]),
                ("settled_by_behind_plane", st.settled_by[1]),
                ("settled_by_in_front_of_plane", st.settled_by[2]),
                ("settled_by_disjoint_projection", st.settled_by[3]),
                ("moves", st.moves),
                ("interpenetration_cuts", st.interpenetration_cuts),
                ("cycle_cuts", st.cycle_cuts),
                ("painter_list", st.list),
            ],
        );
        stats.insert(
            "translucent_painter_order".into(),
            (!layered.is_empty()).into(),
        );
        VisibleSet::exact(screen, pieces, layered, stats, fallbacks)
    }
}

/// Piece `i` of the list (not yet painted or cut).
fn item(items: &[Option<Item>], i: usize) -> &Item {
    items[i].as_ref().expect("in list")
}

/// A piece in the list with what the cheap tests read.
struct Item {
    piece: Piece,
    /// [`depth::range`].
    depth: [f64; 2],
    /// [`bounds`].
    bounds: [f64; 4],
}

impl Item {
    fn new(screen: &ScreenScene, piece: Piece) -> Item {
        Item {
            depth: depth::range(screen, &piece),
            bounds: bounds(&piece),
            piece,
        }
    }
}

/// Test 3 (`p` behind `q`'s plane) or test 4 (`q` in front of `p`'s plane) with `p` first:
/// which of them proves that painting `p` before `q` is right, if either does. Coplanar pieces
/// are ordered by the tie rule.
fn plane_test(screen: &ScreenScene, p: &Piece, q: &Piece) -> Option<usize> {
    let p_behind_on_tie = || tie_key(screen, p) > tie_key(screen, q);
    let (p_nearer, p_farther) = p.sides_of_plane(&q.support);
    if !p_nearer && !p_farther {
        // The same plane.
        return p_behind_on_tie().then_some(1);
    }
    if !p_nearer {
        return Some(1);
    }
    let (_, q_farther) = q.sides_of_plane(&p.support);
    (!q_farther).then_some(2)
}

/// The back-to-front list of `pieces`: see the module docs. `report` gets stage "depth order".
pub fn depth_order(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
) -> (Vec<Piece>, NewellStats) {
    let mut st = NewellStats {
        pieces: pieces.len(),
        ..NewellStats::default()
    };
    let n = pieces.len();
    let mut items: Vec<Option<Item>> = pieces
        .into_iter()
        .map(|p| Some(Item::new(screen, p)))
        .collect();
    // The list is `front` (pieces moved or cut, the head last) then `rest` (the rest, farthest
    // first, as a stack: the head last). `in_rest[i]` is false once piece i left `rest`.
    let mut rest: Vec<usize> = (0..n).collect();
    rest.sort_by(|&i, &j| {
        let (a, b) = (item(&items, i), item(&items, j));
        a.depth[1].total_cmp(&b.depth[1]).then(j.cmp(&i))
    });
    let mut in_rest = vec![true; n];
    let mut front: Vec<usize> = Vec::new();
    // A piece moved to the head since the last piece was painted or cut has `mark == epoch`.
    let mut mark: Vec<u64> = vec![0; n];
    let mut epoch = 1u64;
    let mut order = Vec::with_capacity(n);
    let mut ticker = Ticker::new(report, "depth order", n as u64);
    loop {
        let head = match front.last() {
            Some(&h) => h,
            None => {
                while rest.last().is_some_and(|&r| !in_rest[r]) {
                    rest.pop();
                }
                match rest.last() {
                    Some(&r) => r,
                    None => break,
                }
            }
        };
        let Some(q) = first_hidden_by(screen, &items, head, &front, &rest, &in_rest, &mut st)
        else {
            // Nothing left may be hidden by the head: paint it.
            if front.last() == Some(&head) {
                front.pop();
            } else {
                rest.pop();
                in_rest[head] = false;
            }
            order.push(items[head].take().expect("in list").piece);
            epoch += 1;
            ticker.tick(order.len().min(n) as u64);
            continue;
        };
        let (p_item, q_item) = (item(&items, head), item(&items, q));
        if plane_test(screen, &q_item.piece, &p_item.piece).is_none() {
            // Neither may go first: they pass through each other, and the head straddles q's
            // plane (see the module docs). Cut it there.
            st.interpenetration_cuts += 1;
            let plane = q_item.piece.support.clone();
            let by = q_item.piece.poly;
            cut(
                screen,
                &mut items,
                &mut front,
                &mut in_rest,
                head,
                &plane,
                by,
            );
            mark.resize(items.len(), 0);
            epoch += 1;
            continue;
        }
        if mark[q] != epoch {
            // q may go first: move it to the head.
            st.moves += 1;
            if in_rest[q] {
                in_rest[q] = false;
            } else {
                let at = front.iter().position(|&f| f == q).expect("q is listed");
                front.remove(at);
            }
            front.push(q);
            mark[q] = epoch;
            continue;
        }
        // q moved already: the front of the list from q to the head is a cycle (each piece
        // failed against the next, which was moved ahead of it). Cut one of its pieces by the
        // plane of another that it straddles, the head and q first.
        st.cycle_cuts += 1;
        let at = front
            .iter()
            .position(|&f| f == q)
            .expect("a marked piece is in front");
        let cycle: Vec<usize> = std::iter::once(head)
            .chain(std::iter::once(q))
            .chain(front[at..].iter().copied().filter(|&f| f != head && f != q))
            .collect();
        let straddles = |a: usize, b: usize| {
            let (pa, pb) = (&item(&items, a).piece, &item(&items, b).piece);
            pa.poly != pb.poly && pa.sides_of_plane(&pb.support) == (true, true)
        };
        let (a, b) = cycle
            .iter()
            .flat_map(|&a| cycle.iter().map(move |&b| (a, b)))
            .find(|&(a, b)| a != b && straddles(a, b))
            .expect("a cycle of convex pieces has one straddling the plane of another");
        let plane = item(&items, b).piece.support.clone();
        let by = item(&items, b).piece.poly;
        cut(screen, &mut items, &mut front, &mut in_rest, a, &plane, by);
        mark.resize(items.len(), 0);
        epoch += 1;
    }
    ticker.finish();
    st.list = order.len();
    (order, st)
}

/// The first piece of the list, other than the head, that painting the head first could hide
/// wrongly: every test fails for it.
fn first_hidden_by(
    screen: &ScreenScene,
    items: &[Option<Item>],
    head: usize,
    front: &[usize],
    rest: &[usize],
    in_rest: &[bool],
    st: &mut NewellStats,
) -> Option<usize> {
    let p = items[head].as_ref().expect("in list");
    let mut fails = |q: usize| -> bool {
        let q = items[q].as_ref().expect("in list");
        // Pieces of one polygon never overlap; test 1: p wholly farther than q.
        if q.piece.poly == p.piece.poly || p.depth[0] > q.depth[1] {
            return false;
        }
        st.compared += 1;
        if !overlap(&p.bounds, &q.bounds) {
            st.settled_by[0] += 1;
            return false;
        }
        if let Some(test) = plane_test(screen, &p.piece, &q.piece) {
            st.settled_by[test] += 1;
            return false;
        }
        if separated_on(screen, &p.piece, &q.piece) {
            st.settled_by[3] += 1;
            return false;
        }
        true
    };
    if let Some(&q) = front.iter().rev().find(|&&q| q != head && fails(q)) {
        return Some(q);
    }
    for &q in rest.iter().rev() {
        if !in_rest[q] || q == head {
            continue;
        }
        // `rest` is farthest first: from here on every piece is wholly nearer than p.
        if items[q].as_ref().expect("in list").depth[1] < p.depth[0] {
            break;
        }
        if fails(q) {
            return Some(q);
        }
    }
    None
}

/// Cuts piece `a` by `plane` (the support plane of polygon `by`), which it straddles; its two
/// parts take its place at the front of the list.
fn cut(
    screen: &ScreenScene,
    items: &mut Vec<Option<Item>>,
    front: &mut Vec<usize>,
    in_rest: &mut Vec<bool>,
    a: usize,
    plane: &std::sync::Arc<crate::exact::Plane>,
    by: u32,
) {
    let piece = items[a].take().expect("in list").piece;
    let Split::Both(nearer, farther) = piece.split_by_plane(plane, by) else {
        unreachable!("a piece is cut only by a plane it straddles");
    };
    let parts = [nearer, farther].map(|p| {
        items.push(Some(Item::new(screen, p)));
        in_rest.push(false);
        items.len() - 1
    });
    match front.iter().position(|&f| f == a) {
        Some(at) => {
            front.splice(at..=at, parts);
        }
        None => {
            in_rest[a] = false;
            front.extend(parts);
        }
    }
}

/// The visible set of a back-to-front list, by painting it exactly ([`Canvas`]): the opaque
/// visible pieces, and the translucent pieces' parts that no later opaque piece covers, in
/// the list's order.
pub fn overpaint(
    order: &[Piece],
    translucent: &dyn Fn(u32) -> bool,
) -> (Vec<Piece>, Vec<Fragment>) {
    let mut canvas = Canvas::over(order);
    // Opaque pieces by position in the list, on a grid, for the translucent pieces' cover.
    let mut opaque_after = Live::over(
        order.iter().map(bounds).collect::<Vec<_>>().iter(),
        order.len(),
    );
    let mut layered = Vec::new();
    for piece in order.iter().rev() {
        if translucent(piece.poly) {
            let near = opaque_after.near(&bounds(piece));
            let covers = near.iter().map(|&v| opaque_after.get(v).expect("kept"));
            let parts = subtract_all(piece.clone(), covers);
            layered.extend(
                parts
                    .into_iter()
                    .rev()
                    .map(|p| Fragment::Piece(Box::new(p))),
            );
        } else {
            opaque_after.add(piece.clone(), bounds(piece));
        }
    }
    layered.reverse();
    for piece in order {
        if !translucent(piece.poly) {
            canvas.paint(piece.clone());
        }
    }
    (canvas.into_pieces(), layered)
}

/// Exact overpainting: pieces painted one over another; what shows is what no later piece
/// covers. Invariant: the shown pieces are pairwise disjoint and their union is the union of
/// everything painted.
pub struct Canvas {
    shown: Live,
}

impl Canvas {
    /// An empty canvas for `pieces` (their bounds size its grid).
    pub fn over(pieces: &[Piece]) -> Canvas {
        let boxes: Vec<[f64; 4]> = pieces.iter().map(bounds).collect();
        Canvas {
            shown: Live::over(&boxes, boxes.len()),
        }
    }

    /// Paints `piece` over everything painted so far: every shown piece loses what it covers.
    pub fn paint(&mut self, piece: Piece) {
        let b = bounds(&piece);
        for v in self.shown.near(&b) {
            let under = self.shown.get(v).expect("near returns live pieces");
            if separated(under, &piece) {
                continue;
            }
            let under = self.shown.take(v).expect("live");
            let mut parts = Vec::new();
            subtract(under, &piece, &mut parts);
            for p in parts {
                let pb = bounds(&p);
                self.shown.add(p, pb);
            }
        }
        self.shown.add(piece, b);
    }

    /// The shown pieces.
    pub fn into_pieces(self) -> Vec<Piece> {
        self.shown.into_pieces()
    }
}
