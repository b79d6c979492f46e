//! The kernel's predicates against a slow exact reference in big rationals, on random inputs and
//! on adversarial ones: points exactly on (or one grid unit off) the query plane or line, nearly
//! parallel planes, tiny and extreme coordinates.

mod support;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use proptest::prelude::*;
use sightline::exact::predicates::{
    Crossing, Line, crossing_with_error, depth_order_at, fallback_count, line_side, meet_side,
    orient2d, segments_cross,
};
use sightline::exact::{GRID_MAX, GridPoint, Plane};
use std::cmp::Ordering;

type Q = BigRational;

fn q(v: i128) -> Q {
    Q::from_integer(BigInt::from(v))
}

/// A 256-bit kernel integer (a plane's offset), exactly.
fn qw(v: sightline::exact::I256) -> Q {
    Q::from_integer(v.to_string().parse().expect("an integer"))
}

fn sign(v: &Q) -> Ordering {
    v.cmp(&Q::zero())
}

fn coeffs(p: &Plane) -> [Q; 4] {
    [q(p.a), q(p.b), q(p.c), qw(p.d)]
}

/// (a, b, d) of a line, exactly.
fn line_coeffs(l: &Line) -> [Q; 3] {
    match l {
        // An edge through (px, py) -> (qx, qy): a = py - qy, b = qx - px, d = -(a·px + b·py).
        Line::Edge([[px, py], [qx, qy]]) => {
            let (a, b) = (
                q(*py as i128) - q(*qy as i128),
                q(*qx as i128) - q(*px as i128),
            );
            let d = -(&a * q(*px as i128) + &b * q(*py as i128));
            [a, b, d]
        }
        Line::Vertical(_) => {
            let p = l.vertical_plane().expect("a vertical line");
            [q(p.a), q(p.b), qw(p.d)]
        }
        Line::Cut(p, r) => {
            let [pa, pb, pc, pd] = coeffs(p);
            let [ra, rb, rc, rd] = coeffs(r);
            [
                &rc * &pa - &pc * &ra,
                &rc * &pb - &pc * &rb,
                &rc * &pd - &pc * &rd,
            ]
        }
    }
}

/// Solves the n x n system rows·x = -last column by Gaussian elimination; `None` if singular.
fn solve(mut rows: Vec<Vec<Q>>) -> Option<Vec<Q>> {
    let n = rows.len();
    for col in 0..n {
        let pivot = (col..n).find(|&r| !rows[r][col].is_zero())?;
        rows.swap(col, pivot);
        for r in 0..n {
            if r != col && !rows[r][col].is_zero() {
                let f = &rows[r][col] / &rows[col][col];
                let pivot_row = rows[col].clone();
                for (dst, src) in rows[r].iter_mut().zip(&pivot_row).skip(col) {
                    *dst -= src * &f;
                }
            }
        }
    }
    Some((0..n).map(|i| -(&rows[i][n] / &rows[i][i])).collect())
}

fn meet_reference(p: [&Plane; 3], qp: &Plane) -> Option<Ordering> {
    let x = solve(p.iter().map(|pl| coeffs(pl).to_vec()).collect())?;
    let c = coeffs(qp);
    Some(sign(
        &(&c[0] * &x[0] + &c[1] * &x[1] + &c[2] * &x[2] + &c[3]),
    ))
}

fn crossing(m: [&Line; 2]) -> Option<(Q, Q)> {
    let rows = m.iter().map(|l| line_coeffs(l).to_vec()).collect();
    let x = solve(rows)?;
    Some((x[0].clone(), x[1].clone()))
}

fn line_reference(m: [&Line; 2], l: &Line) -> Option<Ordering> {
    let (x, y) = crossing(m)?;
    let c = line_coeffs(l);
    Some(sign(&(&c[0] * &x + &c[1] * &y + &c[2])))
}

fn depth_reference(m: [&Line; 2], s: &Plane, t: &Plane) -> Option<Ordering> {
    let (x, y) = crossing(m)?;
    let z = |p: &Plane| {
        let c = coeffs(p);
        -(&c[0] * &x + &c[1] * &y + &c[3]) / &c[2]
    };
    Some(z(s).cmp(&z(t)))
}

fn gp(x: i64, y: i64, z: i64) -> GridPoint {
    GridPoint {
        x: x.clamp(-GRID_MAX, GRID_MAX),
        y: y.clamp(-GRID_MAX, GRID_MAX),
        z: z.clamp(-GRID_MAX, GRID_MAX),
    }
}

fn coord(scale: i64) -> impl Strategy<Value = i64> {
    -scale..=scale
}

/// Grid points at one of several scales: tiny, medium, and the full range.
fn point() -> impl Strategy<Value = GridPoint> {
    prop_oneof![
        (coord(3), coord(3), coord(3)),
        (coord(1000), coord(1000), coord(1000)),
        (coord(GRID_MAX), coord(GRID_MAX), coord(GRID_MAX)),
    ]
    .prop_map(|(x, y, z)| gp(x, y, z))
}

fn any_plane() -> impl Strategy<Value = Plane> {
    prop_oneof![
        (point(), point(), point()).prop_filter_map("flat", |(a, b, c)| Plane::through(a, b, c)),
        (point(), point()).prop_filter_map("same xy", |(a, b)| Plane::edge(a, b)),
    ]
}

/// A plane through `g` (support or edge), so that meets built from such planes land on `g`.
fn plane_through(g: GridPoint) -> impl Strategy<Value = Plane> {
    prop_oneof![
        (point(), point()).prop_filter_map("flat", move |(a, b)| Plane::through(g, a, b)),
        point().prop_filter_map("same xy", move |a| Plane::edge(g, a)),
    ]
}

/// A query plane through `g` or through a grid neighbour of `g` (one unit off: the nearest
/// non-zero case the grid allows).
fn query_near(g: GridPoint) -> impl Strategy<Value = Plane> {
    (0..4usize, point(), point()).prop_filter_map("flat", move |(k, a, b)| {
        let h = match k {
            0 => g,
            1 => gp(g.x + 1, g.y, g.z),
            2 => gp(g.x, g.y - 1, g.z),
            _ => gp(g.x, g.y, g.z + 1),
        };
        Plane::through(h, a, b).or_else(|| Plane::edge(h, a))
    })
}

fn support(p: Plane) -> Option<Plane> {
    (p.c > 0).then_some(p)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn meet_side_random(p0 in any_plane(), p1 in any_plane(), p2 in any_plane(), qp in any_plane()) {
        prop_assert_eq!(meet_side([&p0, &p1, &p2], &qp), meet_reference([&p0, &p1, &p2], &qp));
    }

    #[test]
    fn meet_side_on_and_next_to_the_point(
        (p0, p1, p2, qp) in point().prop_flat_map(|g| (plane_through(g), plane_through(g), plane_through(g), query_near(g)))
    ) {
        prop_assert_eq!(meet_side([&p0, &p1, &p2], &qp), meet_reference([&p0, &p1, &p2], &qp));
    }

    #[test]
    fn line_side_random(a in any_plane(), b in any_plane(), c in any_plane(), d in any_plane(), e in any_plane(), f in any_plane()) {
        // Mix edge lines and cut lines (a cut needs two planes, one at least not vertical).
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        let (l0, l1, l2) = (line(a, b), line(c, d), line(e, f));
        prop_assert_eq!(line_side([&l0, &l1], &l2), line_reference([&l0, &l1], &l2));
    }

    #[test]
    fn line_side_through_a_common_point(
        (a, b, c, d, e, f) in point().prop_flat_map(|g| (plane_through(g), plane_through(g), plane_through(g), plane_through(g), plane_through(g), query_near(g)))
    ) {
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        let (l0, l1, l2) = (line(a, b), line(c, d), line(e, f));
        prop_assert_eq!(line_side([&l0, &l1], &l2), line_reference([&l0, &l1], &l2));
    }

    #[test]
    fn depth_order_random(a in any_plane(), b in any_plane(), c in any_plane(), d in any_plane(), s in any_plane(), t in any_plane()) {
        let (Some(s), Some(t)) = (support(s), support(t)) else { return Ok(()); };
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        let (l0, l1) = (line(a, b), line(c, d));
        prop_assert_eq!(depth_order_at([&l0, &l1], &s, &t), depth_reference([&l0, &l1], &s, &t));
    }

    #[test]
    fn depth_order_where_two_faces_meet(
        (a, b, s, t, u) in point().prop_flat_map(|g| (plane_through(g), plane_through(g), plane_through(g), plane_through(g), query_near(g)))
    ) {
        // s and t both pass through g; the crossing of the lines is g's (x, y) when both lines
        // pass through g too: the depths tie exactly there.
        let (Some(s), Some(t)) = (support(s), support(t)) else { return Ok(()); };
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        let (l0, l1) = (line(a, b), line(u, s));
        prop_assert_eq!(depth_order_at([&l0, &l1], &s, &t), depth_reference([&l0, &l1], &s, &t));
    }

    #[test]
    fn orient_and_crossing_match_rationals(p0 in point(), p1 in point(), q0 in point(), q1 in point()) {
        let o = |a: GridPoint, b: GridPoint, c: GridPoint| {
            sign(&((q(b.x as i128) - q(a.x as i128)) * (q(c.y as i128) - q(a.y as i128))
                - (q(b.y as i128) - q(a.y as i128)) * (q(c.x as i128) - q(a.x as i128))))
        };
        prop_assert_eq!(orient2d(p0, p1, q0), o(p0, p1, q0));
        // Reference crossing: parametric solve in rationals.
        let reference = {
            let (dx1, dy1) = (q((p1.x - p0.x) as i128), q((p1.y - p0.y) as i128));
            let (dx2, dy2) = (q((q1.x - q0.x) as i128), q((q1.y - q0.y) as i128));
            let den = &dx1 * &dy2 - &dy1 * &dx2;
            let (ex, ey) = (q((q0.x - p0.x) as i128), q((q0.y - p0.y) as i128));
            if !den.is_zero() {
                let t = (&ex * &dy2 - &ey * &dx2) / &den;
                let u = (&ex * &dy1 - &ey * &dx1) / &den;
                let zero = q(0);
                let one = q(1);
                let inside = |v: &Q| *v >= zero && *v <= one;
                let strict = |v: &Q| *v > zero && *v < one;
                if strict(&t) && strict(&u) { Crossing::Proper }
                else if inside(&t) && inside(&u) { Crossing::Touch }
                else { Crossing::Disjoint }
            } else {
                // Parallel or degenerate: they meet only where an endpoint of one lies on the
                // other (collinear overlaps included).
                let on = |a: GridPoint, b: GridPoint, c: GridPoint| {
                    if a.x == b.x && a.y == b.y {
                        a.x == c.x && a.y == c.y
                    } else {
                        o(a, b, c) == Ordering::Equal
                            && c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x)
                            && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
                    }
                };
                if on(q0, q1, p0) || on(q0, q1, p1) || on(p0, p1, q0) || on(p0, p1, q1) { Crossing::Touch } else { Crossing::Disjoint }
            }
        };
        prop_assert_eq!(segments_cross(p0, p1, q0, q1), reference);
    }
}

/// The point filter: a crossing's f64 point with its error bound (`crossing_with_error`), tested
/// against a line's f64 coefficients (`LineApprox::sign_at`): the bound must hold, and every
/// sign it gives must be the exact one.
fn check_point_filter(l0: &Line, l1: &Line, l2: &Line) -> Result<bool, TestCaseError> {
    let Some(([x, y], e)) = crossing_with_error(l0, l1) else {
        return Ok(false);
    };
    let (rx, ry) = crossing([l0, l1]).expect("a bounded crossing exists");
    let within = |v: f64, r: &Q| {
        let v = Q::from_float(v).unwrap();
        let e = Q::from_float(e).unwrap();
        (&v - r).abs() <= e
    };
    prop_assert!(
        within(x, &rx) && within(y, &ry),
        "crossing bound {e} does not hold"
    );
    let decided = l2.approx().sign_at([x, y, e]);
    if let Some(s) = decided {
        prop_assert_eq!(Some(s), line_reference([l0, l1], l2));
    }
    Ok(decided.is_some())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn point_filter_random(a in any_plane(), b in any_plane(), c in any_plane(), d in any_plane(), e in any_plane(), f in any_plane()) {
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        check_point_filter(&line(a, b), &line(c, d), &line(e, f))?;
    }

    #[test]
    fn point_filter_through_a_common_point(
        (a, b, c, d, e, f) in point().prop_flat_map(|g| (plane_through(g), plane_through(g), plane_through(g), plane_through(g), plane_through(g), query_near(g)))
    ) {
        // The third line passes through the crossing or one unit off it: the filter must
        // abstain or be right.
        let line = |p: Plane, r: Plane| if p.c == 0 && r.c == 0 { Line::vertical(&p) } else { Line::cut(p, r) };
        check_point_filter(&line(a, b), &line(c, d), &line(e, f))?;
    }
}

#[test]
fn adversarial_inputs_reach_the_exact_path() {
    // Three planes through one grid point, queried by a plane through the same point: every
    // determinant is exactly zero, which no f64 filter can certify.
    // Coordinates across the whole grid (|x|, |y|, |z| up to 2^53), so that the exact path
    // works with the widest numbers the grid makes.
    let u = 1i64 << 30;
    let g = GridPoint {
        x: 12345 * u + 7,
        y: -6789 * u - 3,
        z: 424242 * u + 1,
    };
    let far = |x: i64, y: i64, z: i64| GridPoint { x, y, z };
    let m = GRID_MAX;
    let p0 = Plane::through(g, far(8_000_000 * u, 1, 3), far(-2, 7_999_999 * u, -5)).unwrap();
    let p1 = Plane::edge(g, far(-8_000_000 * u, 8_000_000 * u, 0)).unwrap();
    let p2 = Plane::edge(g, far(8_000_000 * u, 7_000_000 * u, 0)).unwrap();
    let qp = Plane::through(g, far(1, -8_000_000 * u, 77), far(-m, m, m)).unwrap();
    let before = fallback_count();
    assert_eq!(meet_side([&p0, &p1, &p2], &qp), Some(Ordering::Equal));
    assert!(fallback_count() > before);
    // One grid unit off: the smallest non-zero value, decided the same way as the reference.
    let q1 = Plane::through(
        far(g.x + 1, g.y, g.z),
        far(1, -8_000_000 * u, 77),
        far(-m, m, m),
    )
    .unwrap();
    assert_eq!(
        meet_side([&p0, &p1, &p2], &q1),
        meet_reference([&p0, &p1, &p2], &q1)
    );
    assert_ne!(meet_side([&p0, &p1, &p2], &q1), Some(Ordering::Equal));
}

/// The pieces' shortcuts (grid corners, face edges, lines through a vertex, cuts by planes the
/// vertex lies on, the meeting point of three cut planes, grid crossings of face edges) settle
/// most exact zeros without a determinant. Each must agree with the big-rational reference at
/// every vertex of every visible piece of tangled scenes, where such zeros abound: shared mesh
/// vertices and edges, and three faces cut pairwise meeting in one point.
#[test]
fn piece_sign_shortcuts_agree_with_the_reference() {
    use sightline::camera::NamedView;
    use sightline::pipeline::prepare;
    use sightline::project::CullMode;
    use sightline::scene::primitives::{interlocked_tori, random_triangle_soup};
    use support::camera::fit;
    use support::strategy::coverage_map;

    let scenes = [random_triangle_soup(16, 7), interlocked_tori(10, 6)];
    let mut zeros = 0;
    for scene in &scenes {
        let cam = fit(scene, NamedView::Iso, false, 64, 64);
        let screen = prepare(scene, &cam, CullMode::Off).screen;
        let (visible, _) = coverage_map(&screen);
        let pieces = &visible.pieces;
        // Every line and plane the visible pieces are made of, tried at every vertex.
        let lines: Vec<Line> = pieces.iter().flat_map(|p| p.lines().cloned()).collect();
        let planes: Vec<std::sync::Arc<Plane>> = pieces.iter().map(|p| p.support.clone()).collect();
        for (i, p) in pieces.iter().enumerate() {
            let n = p.len();
            for k in 0..n {
                let m = [p.line((k + n - 1) % n), p.line(k)];
                for l in lines.iter().skip(i % 29).step_by(29) {
                    let want = line_reference(m, l).expect("adjacent lines cross");
                    zeros += (want == Ordering::Equal) as usize;
                    assert_eq!(
                        p.vertex_line_sign(k, l),
                        want,
                        "piece {i} vertex {k}, {l:?}"
                    );
                }
                for t in planes.iter().skip(i % 11).step_by(11) {
                    let want = depth_reference(m, &p.support, t).expect("adjacent lines cross");
                    zeros += (want == Ordering::Equal) as usize;
                    assert_eq!(
                        p.vertex_plane_sign(k, t),
                        want,
                        "piece {i} vertex {k}, {t:?}"
                    );
                }
            }
        }
    }
    // The scenes must reach the exact zeros the shortcuts exist for.
    eprintln!("{zeros} exact zeros");
    assert!(zeros > 1000, "only {zeros} exact zeros tried");
}

/// Two lines so nearly parallel that the f64 denominator cancels to 0 still get a finite f64
/// crossing (from exact integers), the exact one correctly rounded: vertices drawn never hold
/// NaN.
#[test]
fn crossing_f64_of_nearly_parallel_lines_is_the_exact_crossing_rounded() {
    use sightline::exact::predicates::crossing_f64;
    let big = 1i64 << 60;
    let edge = |a: i64, b: i64, d: i128| {
        Line::vertical(&Plane {
            a: a as i128,
            b: b as i128,
            c: 0,
            d: sightline::exact::w256(d),
        })
    };
    // det = (2^60 + 1)(2^60 + 3) - (2^60 + 4)·2^60 = 3, but both products round to 2^120 in
    // f64. Rounding the numerators and then dividing by 3 gives an x one ulp off here.
    let l = edge(big + 1, big, 54);
    let m = edge(big + 4, big + 3, 55);
    let [x, y] = crossing_f64(&l, &m);
    assert!(x.is_finite() && y.is_finite(), "{x} {y}");
    let (rx, ry) = crossing([&l, &m]).unwrap();
    let rounded = |r: &Q| num_traits::ToPrimitive::to_f64(r).unwrap();
    assert_eq!([x, y], [rounded(&rx), rounded(&ry)], "{rx} {ry}");
}
