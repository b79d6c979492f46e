//! Exact points along a line of the screen, and their order.
//!
//! A drawn line lies on a [`Carrier`]: a kernel [`Line`] (a face edge through two grid points,
//! or the projection of two planes' meeting line). A point on it is a grid point or where
//! another kernel line crosses it ([`At`]); it is never rounded. Its position along the carrier
//! is an exact rational ([`Param`]): its x (or y, for a steep carrier) coordinate, signed so
//! that it grows along the carrier's direction. Two positions are compared in f64 when their
//! proven error bounds ([`crossing_with_error`]) separate them, and otherwise exactly, by
//! cross-multiplying 1024-bit integers (crossing coordinates are quotients of numerators below
//! 2^495 by denominators below 2^440, so products stay below 2^935). The only rounding is
//! [`Carrier::pixel`]: each coordinate correctly rounded once, a function of the exact point
//! alone, so a point named by two different line pairs gets the same bits.

use crate::exact::Samples;
use crate::exact::U;
use crate::exact::predicates::crossing_rounded;
use crate::exact::predicates::{Line, Wide, crossing_with_error, heading};
use bnum::cast::As;
use bnum::types::I1024;
use std::cmp::Ordering;

fn wide(v: i64) -> Wide {
    v.as_()
}

/// A point on a carrier.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum At {
    /// A grid point on the carrier (x, y).
    Grid([i64; 2]),
    /// Where `Line` crosses the carrier (not parallel to it).
    Cross(Line),
}

/// An exact position along a carrier: an f64 value with a proven error bound, and what it
/// takes to compute it exactly when two positions are too close for the bounds to decide.
#[derive(Clone, Debug)]
pub struct Param<'a> {
    /// The position, within `err` of the exact one.
    approx: f64,
    err: f64,
    /// The point and its carrier, for the exact comparison.
    at: At,
    carrier: &'a Carrier,
}

impl Param<'_> {
    /// The point.
    pub fn at(&self) -> At {
        self.at.clone()
    }

    /// `num / den` (`den > 0`), exactly.
    fn exact(&self) -> (Wide, Wide) {
        let (num, den) = match &self.at {
            At::Grid([x, y]) => (wide(if self.carrier.along_x { *x } else { *y }), wide(1)),
            At::Cross(m) => {
                let [a0, b0, d0] = self.carrier.line.exact();
                let [a1, b1, d1] = m.exact();
                let den = a0 * b1 - a1 * b0;
                debug_assert!(!den.is_zero(), "a crossing line is not parallel");
                let num = if self.carrier.along_x {
                    b0 * d1 - b1 * d0
                } else {
                    a1 * d0 - a0 * d1
                };
                if den.is_negative() {
                    (-num, -den)
                } else {
                    (num, den)
                }
            }
        };
        (if self.carrier.negate { -num } else { num }, den)
    }
}

impl PartialEq for Param<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Param<'_> {}

impl PartialOrd for Param<'_> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Param<'_> {
    fn cmp(&self, other: &Self) -> Ordering {
        // The difference of the two f64 values errs by their bounds and one rounding.
        let diff = self.approx - other.approx;
        let bound = (self.err + other.err) * (1.0 + 4.0 * U)
            + 4.0 * U * self.approx.abs().max(other.approx.abs());
        if diff > bound {
            return Ordering::Greater;
        }
        if diff < -bound {
            return Ordering::Less;
        }
        match (&self.at, &other.at) {
            // Both exact in f64 (grid coordinates are integers below 2^54).
            (At::Grid(_), At::Grid(_)) => return self.approx.total_cmp(&other.approx),
            // A line through the grid point crosses the carrier there.
            (At::Grid([x, y]), At::Cross(m)) | (At::Cross(m), At::Grid([x, y]))
                if m.sign_at_grid(*x, *y) == Ordering::Equal =>
            {
                return Ordering::Equal;
            }
            _ => {}
        }
        let ((n0, d0), (n1, d1)) = (self.exact(), other.exact());
        if d0 == d1 {
            return n0.cmp(&n1);
        }
        let big = |v: Wide| -> I1024 { v.as_() };
        (big(n0) * big(d1)).cmp(&(big(n1) * big(d0)))
    }
}

/// A line that drawn segments lie on, with what it takes to order points along it.
#[derive(Clone, Debug)]
pub struct Carrier {
    /// The kernel line.
    pub line: Line,
    /// Positions are x coordinates (else y).
    along_x: bool,
    /// Positions are negated so that they grow along the direction (b, -a).
    negate: bool,
}

impl Carrier {
    /// The carrier of `line`, directed along (b, -a): for an edge line `Plane::edge(p, q)`, from
    /// p to q.
    pub fn new(line: Line) -> Carrier {
        // Only the signs and the larger of |a| and |b| matter: exact in i64 for an edge line.
        let (along_x, a_negative, b_negative) = match line.vertical_coefficients() {
            Some([a, b, _]) => (b.unsigned_abs() >= a.unsigned_abs(), a < 0, b < 0),
            None => {
                let [a, b, _] = line.exact();
                (
                    b.unsigned_abs() >= a.unsigned_abs(),
                    a.is_negative(),
                    b.is_negative(),
                )
            }
        };
        // Moving along (b, -a), x grows when b > 0 and y grows when a < 0.
        let negate = if along_x { b_negative } else { !a_negative };
        Carrier {
            line,
            along_x,
            negate,
        }
    }

    /// The position of `at` along the carrier.
    pub fn param(&self, at: &At) -> Param<'_> {
        let (value, err) = match at {
            At::Grid([x, y]) => (if self.along_x { *x } else { *y } as f64, 0.0),
            At::Cross(m) => match crossing_with_error(&self.line, m) {
                Some(([x, y], e)) => (if self.along_x { x } else { y }, e),
                None => (0.0, f64::INFINITY),
            },
        };
        Param {
            approx: if self.negate { -value } else { value },
            err,
            at: at.clone(),
            carrier: self,
        }
    }

    /// `at` in pixels: its exact grid coordinates correctly rounded to f64, mapped to pixels as
    /// the filled drawing maps its vertices.
    pub fn pixel(&self, at: &At, s: &Samples) -> [f64; 2] {
        let [x, y] = match at {
            At::Grid([x, y]) => [*x as f64, *y as f64],
            At::Cross(m) => {
                crossing_rounded(&self.line, m).expect("a crossing line is not parallel")
            }
        };
        [s.col_of(x), s.row_of(y)]
    }

    /// The positions of two points in the carrier's direction; `None` when they are the same
    /// point.
    pub fn ordered(&self, a: At, b: At) -> Option<[Param<'_>; 2]> {
        let (pa, pb) = (self.param(&a), self.param(&b));
        match pa.cmp(&pb) {
            Ordering::Less => Some([pa, pb]),
            Ordering::Greater => Some([pb, pa]),
            Ordering::Equal => None,
        }
    }

    /// Whether `m` crosses the carrier (is not parallel to it).
    pub fn crosses(&self, m: &Line) -> bool {
        self.heading(m) != Ordering::Equal
    }

    /// How `m` runs along the carrier: `Greater` when its value grows in the carrier's direction
    /// (its positive side lies ahead), `Less` when it falls, `Equal` when parallel.
    pub fn heading(&self, m: &Line) -> Ordering {
        heading(&self.line, m)
    }

    /// The sign of `m` on the carrier when they are parallel (the same everywhere on it).
    pub fn side_of_parallel(&self, m: &Line) -> Ordering {
        let [a0, b0, d0] = self.line.exact();
        let [a1, b1, d1] = m.exact();
        // m at a point of the carrier, (0, -d0/b0) or (-d0/a0, 0), times that divisor.
        let (value, divisor) = if !b0.is_zero() {
            (d1 * b0 - b1 * d0, b0)
        } else {
            (d1 * a0 - a1 * d0, a0)
        };
        let s = value.cmp(&wide(0));
        if divisor.is_negative() {
            s.reverse()
        } else {
            s
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;

    fn g(x: i64, y: i64) -> GridPoint {
        GridPoint { x, y, z: 0 }
    }

    fn edge(p: (i64, i64), q: (i64, i64)) -> Line {
        Line::edge(g(p.0, p.1), g(q.0, q.1)).unwrap()
    }

    #[test]
    fn positions_grow_along_the_carrier_in_every_direction() {
        for (p, q) in [
            ((0, 0), (10, 3)),
            ((10, 3), (0, 0)),
            ((0, 0), (2, 9)),
            ((2, 9), (0, 0)),
            ((0, 5), (0, -5)),
            ((-4, 1), (7, 1)),
        ] {
            let c = Carrier::new(edge(p, q));
            let (a, b) = (
                c.param(&At::Grid([p.0, p.1])),
                c.param(&At::Grid([q.0, q.1])),
            );
            assert!(a < b, "{p:?} -> {q:?}");
        }
    }

    #[test]
    fn a_crossing_is_ordered_exactly_and_rounds_to_its_point() {
        // The carrier y = x/3 from (0,0) to (30,10); the vertical x = 7 crosses it at (7, 7/3).
        let c = Carrier::new(edge((0, 0), (30, 10)));
        let cross = At::Cross(edge((7, -100), (7, 100)));
        assert!(c.param(&At::Grid([6, 2])) < c.param(&cross));
        assert!(c.param(&cross) < c.param(&At::Grid([9, 3])));
        assert_eq!(c.param(&cross), c.param(&At::Cross(edge((7, 50), (7, 60)))));
        let s = Samples::new(2, 2);
        let px = c.pixel(&cross, &s);
        assert_eq!(px, [s.col_of(7.0), s.row_of(7.0 / 3.0)]);
    }

    #[test]
    fn headings_and_parallel_sides() {
        let c = Carrier::new(edge((0, 0), (10, 0)));
        // Positive on the left of (0,5)->(0,-5): x < 0 side... Plane::edge is positive on the
        // left of p->q; going down, the left is +x, so its value grows along the carrier.
        assert_eq!(c.heading(&edge((0, 5), (0, -5))), Ordering::Greater);
        assert_eq!(c.heading(&edge((0, -5), (0, 5))), Ordering::Less);
        assert_eq!(c.heading(&edge((0, 3), (4, 3))), Ordering::Equal);
        // y = 3, directed +x: positive on its left (y > 3); the carrier y = 0 is on its negative side.
        assert_eq!(c.side_of_parallel(&edge((0, 3), (4, 3))), Ordering::Less);
        assert_eq!(c.side_of_parallel(&edge((4, 3), (0, 3))), Ordering::Greater);
        assert_eq!(c.side_of_parallel(&edge((1, 0), (5, 0))), Ordering::Equal);
        let v = Carrier::new(edge((2, 0), (2, 10)));
        assert_eq!(v.side_of_parallel(&edge((5, 0), (5, 1))), Ordering::Greater);
    }
}
