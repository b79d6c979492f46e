//! Every boundary of every visible piece knows where it comes from, and says so truly: the
//! line of a piece is exactly the line its [`Boundary`] names (a side of a polygon's outline, a
//! diagonal of its decomposition, the meeting of two polygons' planes, a screen split of a BSP or
//! a quadtree), for every exact strategy of the method registry, on interpenetrating soups, tori,
//! fixtures and a scene cut by the near plane. And the sides of screen polygons say which face edge or clip plane they lie on.

use glam::DVec3;
use sightline::camera::{Camera, NamedView, Projection};
use sightline::exact::Plane;
use sightline::exact::polygon::{Boundary, Piece};
use sightline::exact::predicates::Line;
use sightline::methods::{Engine, METHODS};
use sightline::pipeline::prepare;
use sightline::project::{ClipPlane, CullMode, ScreenScene, Side};
use sightline::scene::{Material, Scene, SceneBuilder, primitives};
use sightline::visibility::{CoverageMap, Fragment, Strategy};

/// Is `l` the edge line through `p` and `q`, either way round?
fn is_edge_through(
    l: &Line,
    p: &sightline::exact::GridPoint,
    q: &sightline::exact::GridPoint,
) -> bool {
    let Some(e) = Plane::edge(*p, *q) else {
        return false;
    };
    l.vertical_plane()
        .is_some_and(|f| f == e || f == e.negated())
}

/// Checks one piece's boundaries against its lines; counts each kind seen.
fn check_piece(screen: &ScreenScene, piece: &Piece, seen: &mut [usize; 4]) {
    assert_eq!(piece.lines().len(), piece.boundaries().len());
    for (line, boundary) in piece.lines().zip(piece.boundaries()) {
        match boundary {
            Boundary::Outline { poly, side } => {
                let c = screen.corners(&screen.polys[poly as usize]);
                let (p, q) = (c[side as usize], c[(side as usize + 1) % c.len()]);
                assert!(
                    is_edge_through(line, &p, &q),
                    "{boundary:?}: {line:?} is not the side {p:?} -> {q:?}"
                );
                seen[0] += 1;
            }
            Boundary::Diagonal { poly } => {
                let c = screen.corners(&screen.polys[poly as usize]);
                let through = (0..c.len())
                    .flat_map(|i| (i + 1..c.len()).map(move |j| (i, j)))
                    .any(|(i, j)| is_edge_through(line, &c[i], &c[j]));
                assert!(through, "{boundary:?}: {line:?} joins no two corners");
                seen[1] += 1;
            }
            Boundary::Cut { a, b } => {
                let (pa, pb) = (
                    screen.plane(&screen.polys[a as usize]),
                    screen.plane(&screen.polys[b as usize]),
                );
                assert!(
                    *line == Line::cut(pa, pb) || *line == Line::cut(pb, pa),
                    "{boundary:?}: {line:?}"
                );
                seen[2] += 1;
            }
            Boundary::ScreenSplit => {
                assert!(
                    line.vertical_plane()
                        .is_some_and(|e| e.c == 0 && (e.a == 0 || e.b == 0)),
                    "{line:?} is not a vertical or horizontal screen line"
                );
                seen[3] += 1;
            }
        }
    }
}

/// Runs every exact strategy of the registry on `scene` seen by `camera`; returns the boundary
/// kinds seen.
fn check_scene(scene: &Scene, camera: &Camera) -> [usize; 4] {
    let screen = prepare(scene, camera, CullMode::Auto).screen;
    let mut seen = [0; 4];
    let translucent = |k: u32| k.is_multiple_of(5);
    let exact = METHODS
        .iter()
        .filter(|m| m.exact)
        .filter_map(|m| match m.engine {
            Engine::Object(s) => Some(s),
            Engine::Image(_) => None,
        });
    for strategy in exact {
        for layered in [false, true] {
            let opaque = |_: u32| false;
            let which: &dyn Fn(u32) -> bool = if layered { &translucent } else { &opaque };
            let v = strategy.visible_set(&screen, which, None);
            for p in &v.pieces {
                check_piece(&screen, p, &mut seen);
            }
            for f in &v.layered {
                if let Fragment::Piece(p) = f {
                    check_piece(&screen, p, &mut seen);
                }
            }
        }
    }
    seen
}

/// One face in the plane z = 0 with corners `pts`, and an orthographic camera looking at it
/// head-on, framing it, `size` pixels square.
fn flat_face(pts: &[[f64; 2]], size: u32) -> (Scene, Camera) {
    let mut b = SceneBuilder::new("face");
    let m = b.add_material(Material::default());
    b.begin_mesh("face");
    let v: Vec<u32> = pts
        .iter()
        .map(|&[x, y]| b.add_vertex(DVec3::new(x, y, 0.0)))
        .collect();
    b.add_face(&v, m);
    let scene = b.finish().unwrap();
    let (lo, hi) = scene.bounds().unwrap();
    let centre = (lo + hi) / 2.0;
    let camera = Camera {
        eye: centre + DVec3::Z * 5.0,
        target: centre,
        up: DVec3::Y,
        projection: Projection::Orthographic {
            height: (hi - lo).max_element() + 1.0,
        },
        near: 1.0,
        far: 10.0,
        width: size,
        height: size,
    };
    (scene, camera)
}

fn iso(scene: &Scene, size: u32) -> Camera {
    Camera::fit(
        NamedView::Iso,
        scene.bounds().unwrap(),
        false,
        40.0,
        size,
        size,
    )
}

#[test]
fn boundaries_name_their_lines_on_interpenetrating_soups() {
    let mut total = [0; 4];
    for seed in 0..12 {
        let scene = primitives::random_triangle_soup(40, seed);
        let seen = check_scene(&scene, &iso(&scene, 64));
        for k in 0..4 {
            total[k] += seen[k];
        }
    }
    // Soups have outline sides and cuts; the BSP balances with screen lines.
    assert!(total[0] > 0 && total[2] > 0 && total[3] > 0, "{total:?}");
}

#[test]
fn boundaries_name_their_lines_on_tori_and_fixtures() {
    let tori = primitives::interlocked_tori(24, 12);
    check_scene(&tori, &iso(&tori, 96));
    let mut total = [0; 4];
    for file in [
        "fixtures/cube.obj",
        "fixtures/cyclic_bars.obj",
        "fixtures/interpenetrating.obj",
        "fixtures/t_junction.obj",
        "fixtures/primitives.x3d",
        "fixtures/two_objects.obj",
    ] {
        let scene = sightline::load(std::path::Path::new(file), None).unwrap();
        let seen = check_scene(&scene, &iso(&scene, 96));
        for k in 0..4 {
            total[k] += seen[k];
        }
    }
    assert!(total[0] > 0 && total[2] > 0, "{total:?}");
}

/// An L-shaped (non-convex) face is decomposed: the decomposition's diagonal is marked as such,
/// never as an edge of the face.
#[test]
fn a_non_convex_face_has_a_diagonal_boundary() {
    let (scene, camera) = flat_face(
        &[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ],
        32,
    );
    let seen = check_scene(&scene, &camera);
    assert!(seen[1] > 0, "{seen:?}");
    assert_eq!(seen[2], 0, "one face: no cuts");
}

/// A quad crossing the near plane keeps its two whole edges and two cut ones, and gains a side
/// along the near plane; sides of faces the clip does not touch are their edges in order.
#[test]
fn sides_of_screen_polygons_name_face_edges_and_clip_planes() {
    let mut b = SceneBuilder::new("near");
    let m = b.add_material(Material::default());
    b.begin_mesh("quad");
    // A floor quad from z = -4 to z = 4 seen from z = 3: the near plane at distance 0.5 cuts it
    // (low and narrow enough that the cut lies inside the guard band, which would cut first).
    let v: Vec<u32> = [[-0.2, -4.0], [0.2, -4.0], [0.2, 4.0], [-0.2, 4.0]]
        .iter()
        .map(|&[x, z]| b.add_vertex(DVec3::new(x, -0.2, z)))
        .collect();
    b.add_face(&v, m);
    b.begin_mesh("far");
    let w: Vec<u32> = [[-1.0, -6.0], [1.0, -6.0], [0.0, -5.0]]
        .iter()
        .map(|&[x, y]| b.add_vertex(DVec3::new(x, y + 5.0, -8.0)))
        .collect();
    b.add_face(&w, m);
    let scene = b.finish().unwrap();
    let camera = Camera {
        eye: DVec3::new(0.0, 0.0, 3.0),
        target: DVec3::new(0.0, 0.0, 0.0),
        up: DVec3::Y,
        projection: Projection::Perspective { fovy_deg: 60.0 },
        near: 0.5,
        far: 100.0,
        width: 64,
        height: 64,
    };
    let screen = prepare(&scene, &camera, CullMode::Off).screen;
    assert_eq!(screen.polys.len(), 2);
    let quad = screen.sides(&screen.polys[0]);
    assert_eq!(
        quad[..],
        [
            Side::Edge(0),
            Side::Edge(1),
            Side::Clip(ClipPlane::Near),
            Side::Edge(3)
        ],
        "the near plane cuts edges 1 and 3 and replaces edge 2"
    );
    let tri = screen.sides(&screen.polys[1]);
    assert_eq!(tri[..], [Side::Edge(0), Side::Edge(1), Side::Edge(2)]);
    check_scene(&scene, &camera);
}

/// A face whose outline has straight corners (T-junction vertices) and a notch: its convex
/// decomposition must not merge pieces so that a diagonal runs on from an outline side (the
/// piece would drop the straight corner between them and name the whole line an outline side).
/// Every outline-labelled side of every piece lies within the run of collinear outline sides
/// its boundary names.
#[test]
fn outline_sides_do_not_run_on_into_diagonals() {
    let (scene, camera) = flat_face(
        &[
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [4.0, 0.0],
            [4.0, 3.0],
            [3.0, 3.0],
            [3.0, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ],
        64,
    );
    let screen = prepare(&scene, &camera, CullMode::Off).screen;
    let c = screen.corners(&screen.polys[0]);
    let n = c.len();
    let visible = CoverageMap.visible_set(&screen, &|_| false, None);
    let mut outline_sides = 0;
    for piece in &visible.pieces {
        let m = piece.len();
        for k in 0..m {
            let Boundary::Outline { side, .. } = piece.boundary(k) else {
                continue;
            };
            outline_sides += 1;
            // The run of collinear sides from `side`: its corners, first to last.
            let side = side as usize;
            let mut last = (side + 1) % n;
            while sightline::exact::predicates::orient2d(c[side], c[last], c[(last + 1) % n])
                == std::cmp::Ordering::Equal
            {
                last = (last + 1) % n;
            }
            let (p, q) = (c[side], c[last]);
            // The piece side runs from vertex k to vertex k + 1 (grid corners here: one face).
            for end in [piece.corner(k), piece.corner((k + 1) % m)] {
                let [x, y] = end.expect("a lone face's piece has grid corners");
                let within = (p.x.min(q.x)..=p.x.max(q.x)).contains(&x)
                    && (p.y.min(q.y)..=p.y.max(q.y)).contains(&y);
                assert!(within, "side {side}: end ({x}, {y}) is off {p:?} -> {q:?}");
            }
        }
    }
    assert!(outline_sides >= 6, "{outline_sides}");
}
