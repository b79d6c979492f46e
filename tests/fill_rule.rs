//! The fill rule: polygons tiling a region cover each pixel centre inside it exactly once, with
//! edges and vertices placed exactly on pixel centres.

mod support;

use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::raster::EMPTY;
use sightline::scene::SceneBuilder;
// The lattice camera's image is 64 x 32, powers of two: pixel centres fall exactly on the
// snapping grid, and `lattice_point(i, j, z)` is the centre of pixel (i, j).
use support::camera::{LATTICE_H as H, LATTICE_W as W, lattice_camera, lattice_point};
use support::rng::Rng;

/// Tiles the pixel-centre rectangle [i0, i0 + step·n] x [j0, j0 + step·m] with triangles (and
/// every third cell a quad), vertices on pixel centres; `jitter` moves interior vertices off them.
fn tiling(
    i0: i64,
    j0: i64,
    step: i64,
    n: i64,
    m: i64,
    jitter: f64,
    z_tilt: f64,
) -> sightline::Scene {
    let mut rng = Rng(7);
    let mut b = SceneBuilder::new("tiles");
    let mat = b.default_material();
    let mut idx = vec![0u32; ((n + 1) * (m + 1)) as usize];
    for y in 0..=m {
        for x in 0..=n {
            let mut p = lattice_point(i0 + step * x, j0 + step * y, 0.0);
            if x > 0 && x < n && y > 0 && y < m {
                p.x += rng.range(-jitter, jitter);
                p.y += rng.range(-jitter, jitter);
            }
            // A tilted plane: coplanar corners, depth varying across the image.
            p.z = z_tilt * (p.x + 0.5 * p.y);
            idx[(y * (n + 1) + x) as usize] = b.add_vertex(p);
        }
    }
    let v = |x: i64, y: i64| idx[(y * (n + 1) + x) as usize];
    for y in 0..m {
        for x in 0..n {
            // Rows go downward on screen, so (x, y+1) is below (x, y): keep the winding CCW.
            let (a, bb, c, d) = (v(x, y + 1), v(x + 1, y + 1), v(x + 1, y), v(x, y));
            if (x + y) % 3 == 0 && jitter == 0.0 {
                b.add_face(&[a, bb, c, d], mat);
            } else if (x + y) % 2 == 0 {
                b.add_face(&[a, bb, c], mat);
                b.add_face(&[a, c, d], mat);
            } else {
                b.add_face(&[a, bb, d], mat);
                b.add_face(&[bb, c, d], mat);
            }
        }
    }
    b.finish().unwrap()
}

fn check_exact_once(scene: &sightline::Scene, i0: i64, j0: i64, i1: i64, j1: i64) -> u64 {
    let (_, zb) = render_zbuffer(scene, &lattice_camera(), CullMode::Off, |_| {});
    let mut covered = 0u64;
    for j in 0..H as i64 {
        for i in 0..W as i64 {
            let hit = zb.poly[(j * W as i64 + i) as usize] != EMPTY;
            // Left and bottom boundaries are in, right and top are out (rows grow downward).
            let expect = i >= i0 && i < i1 && j > j0 && j <= j1;
            assert_eq!(hit, expect, "pixel ({i}, {j})");
            covered += hit as u64;
        }
    }
    assert_eq!(
        zb.stats.fragments, covered,
        "some pixel centre was covered by two polygons"
    );
    assert_eq!(zb.stats.depth_ties, 0);
    zb.stats.column_fallbacks
}

#[test]
fn grid_on_pixel_centres_covers_each_centre_once() {
    for tilt in [0.0, 0.7] {
        let scene = tiling(4, 3, 5, 10, 5, 0.0, tilt);
        let exact_ties = check_exact_once(&scene, 4, 3, 54, 28);
        assert!(
            exact_ties > 0,
            "edges through centres must reach the exact path"
        );
    }
}

#[test]
fn jittered_tiling_covers_each_centre_once() {
    for tilt in [0.0, -0.4] {
        let scene = tiling(2, 2, 6, 9, 4, 0.05, tilt);
        let _ = check_exact_once(&scene, 2, 2, 56, 26);
    }
}

#[test]
fn fine_grid_with_edges_through_every_centre() {
    let scene = tiling(1, 1, 1, 60, 28, 0.0, 0.3);
    let _ = check_exact_once(&scene, 1, 1, 61, 29);
}
