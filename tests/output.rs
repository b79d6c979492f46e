//! Output of drawings (SVG, JSON, pixel-centre rasterization) and the painter baseline measured
//! against the exact z-buffer.

mod support;

use glam::DVec3;
use sightline::camera::Camera;
use sightline::methods::{METHODS, method};
use sightline::output::drawing::{DrawItem, Drawing};
use sightline::output::json::write_json;
use sightline::output::raster_drawing::{colors, face_ids};
use sightline::output::svg::{SvgOptions, write_svg};
use sightline::pipeline::{Fill, prepare, render_zbuffer};
use sightline::project::CullMode;
use sightline::scene::primitives::sphere_scene;
use sightline::scene::{Material, Scene, SceneBuilder};
use support::camera::{front_ortho, ortho_down_z, scene_camera, spec_camera};
use support::fixtures::fixture;
use support::oracle::{assert_seed_transparent_colours, interior_mismatches};
use support::scenes::{add_triangle, random_triangles};
use support::strategy::{
    CoverageMap, Painter, Strategy, drawing_of, exact_drawing, exact_strategies, painter_drawing,
};

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// A 10x10 square with a 4x4 hole, over a red strip, on a 12x12 image.
fn holed_drawing() -> Drawing {
    Drawing {
        width: 12,
        height: 12,
        background: Some([1.0, 1.0, 1.0]),
        items: vec![
            DrawItem::new(3, vec![rect(0.0, 5.0, 12.0, 7.0)], [1.0, 0.0, 0.0], 1.0),
            DrawItem::new(
                8,
                vec![rect(1.0, 1.0, 11.0, 11.0), rect(4.0, 4.0, 8.0, 8.0)],
                [0.0, 0.0, 1.0],
                0.5,
            ),
        ],
        seams: Default::default(),
        opaque_disjoint: false,
    }
}

fn svg_paths<'a>(doc: &'a roxmltree::Document<'a>) -> Vec<roxmltree::Node<'a, 'a>> {
    doc.descendants()
        .filter(|n| n.has_tag_name("path"))
        .collect()
}

/// The numbers of an SVG path's `d`, in order.
fn path_numbers(d: &str) -> Vec<f64> {
    d.split(|c: char| c == ' ' || c.is_ascii_alphabetic() && c != 'e')
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect()
}

// ---------------------------------------------------------------------------------------------
// SVG

#[test]
fn svg_keeps_every_digit_of_every_coordinate() {
    let (a, b) = (0.1 + 0.2, 1234.5678901234567);
    let d = Drawing {
        width: 2000,
        height: 10,
        background: None,
        items: vec![DrawItem::new(
            0,
            vec![vec![[a, 1.0], [b, -0.0], [b, 2.0 / 3.0]]],
            [0.5; 3],
            1.0,
        )],
        seams: Default::default(),
        opaque_disjoint: false,
    };
    let svg = write_svg(&d, &SvgOptions::default());
    assert!(svg.contains("0.30000000000000004"), "{svg}");
    assert!(svg.contains("1234.5678901234567"), "{svg}");
    assert!(
        !svg.contains("-0 ") && !svg.contains("-0L"),
        "-0 is written as 0: {svg}"
    );
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let paths = svg_paths(&doc);
    let nums = path_numbers(paths[0].attribute("d").unwrap());
    let want: Vec<f64> = d.items[0].rings[0].iter().flatten().copied().collect();
    assert_eq!(nums.len(), want.len());
    for (n, w) in nums.iter().zip(&want) {
        assert_eq!(n.to_bits(), (w + 0.0).to_bits());
    }
}

#[test]
fn svg_structure_attributes_and_holes() {
    let d = holed_drawing();
    let svg = write_svg(&d, &SvgOptions::default());
    let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.attribute("viewBox"), Some("0 0 12 12"));
    assert_eq!(root.attribute("width"), Some("12"));
    assert_eq!(root.attribute("height"), Some("12"));
    assert_eq!(root.attribute("shape-rendering"), None);
    // The background rectangle comes first.
    let bg = root.descendants().find(|n| n.has_tag_name("rect")).unwrap();
    assert_eq!(bg.attribute("fill"), Some("#ffffff"));
    let paths = svg_paths(&doc);
    assert_eq!(paths.len(), 2);
    let faces: Vec<&str> = paths
        .iter()
        .map(|p| p.attribute("data-face").unwrap())
        .collect();
    assert_eq!(faces, ["3", "8"]);
    for p in &paths {
        assert_eq!(p.attribute("fill-rule"), Some("evenodd"));
    }
    assert_eq!(paths[0].attribute("fill"), Some("#ff0000"));
    assert_eq!(paths[0].attribute("fill-opacity"), None);
    assert_eq!(paths[1].attribute("fill"), Some("#0000ff"));
    assert_eq!(paths[1].attribute("fill-opacity"), Some("0.5"));
    // The hole is a second ring of the same path.
    let dd = paths[1].attribute("d").unwrap();
    assert_eq!(dd, "M1 1L11 1L11 11L1 11ZM4 4L8 4L8 8L4 8Z");
}

#[test]
fn svg_options_and_no_background() {
    let mut d = holed_drawing();
    d.background = None;
    let opts = SvgOptions {
        stroke: Some(([0.0, 0.0, 0.0], 0.25)),
        crisp: true,
    };
    let svg = write_svg(&d, &opts);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert!(!doc.descendants().any(|n| n.has_tag_name("rect")));
    assert_eq!(
        doc.root_element().attribute("shape-rendering"),
        Some("crispEdges")
    );
    let g = doc.descendants().find(|n| n.has_tag_name("g")).unwrap();
    assert_eq!(g.attribute("stroke"), Some("#000000"));
    assert_eq!(g.attribute("stroke-width"), Some("0.25"));
}

#[test]
fn svg_and_json_are_deterministic() {
    let scene = fixture("primitives.x3d");
    let cam = spec_camera(&scene, (320, 240));
    let run = || {
        let screen = prepare(&scene, &cam, CullMode::Auto).screen;
        let mut r = painter_drawing(&scene, &screen, &cam, Fill::Shade);
        r.stats.remove("sort_seconds"); // a timing, not part of the picture
        (
            write_svg(&r.drawing, &SvgOptions::default()),
            write_json(&r.drawing, &scene, &r.stats),
        )
    };
    let (s1, j1) = run();
    let (s2, j2) = run();
    assert_eq!(s1.as_bytes(), s2.as_bytes());
    assert_eq!(j1.as_bytes(), j2.as_bytes());
    roxmltree::Document::parse(&s1).unwrap();
}

// ---------------------------------------------------------------------------------------------
// JSON

#[test]
fn json_parses_back_grouped_by_face_with_materials_and_stats() {
    let mut b = SceneBuilder::new("json");
    b.begin_mesh("m");
    let glass = b.add_material(Material {
        name: "glass".into(),
        diffuse: [0.1, 0.2, 0.3],
        emissive: [0.0, 0.5, 0.0],
        transparency: 0.25,
        two_sided: true,
    });
    let v: Vec<u32> = [DVec3::ZERO, DVec3::X, DVec3::Y]
        .iter()
        .map(|&p| b.add_vertex(p))
        .collect();
    b.add_face(&v, glass);
    let scene = b.finish().unwrap();

    // Face 5 drawn twice (a split face), face 2 between: grouped, ascending, painter order kept.
    let mut d = holed_drawing();
    d.items = vec![
        DrawItem::new(5, vec![rect(0.0, 0.0, 1.0, 1.0)], [1.0; 3], 1.0),
        DrawItem::new(2, vec![rect(-0.0, 1.0, 2.5, 3.0)], [1.0; 3], 1.0),
        DrawItem::new(
            5,
            vec![rect(4.0, 4.0, 6.0, 6.0), rect(4.5, 4.5, 5.5, 5.5)],
            [1.0; 3],
            1.0,
        ),
    ];
    let mut stats = serde_json::Map::new();
    stats.insert("faces_drawn".into(), 3.into());
    stats.insert("method".into(), "test".into());
    let text = write_json(&d, &scene, &stats);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();

    // Keys in the documented order.
    let pos = |k: &str| text.find(&format!("\"{k}\"")).unwrap();
    assert!(pos("width") < pos("height") && pos("height") < pos("faces"));
    assert!(pos("faces") < pos("stats"));

    assert_eq!(v["width"], 12);
    assert_eq!(v["height"], 12);
    let faces = v["faces"].as_array().unwrap();
    let ids: Vec<u64> = faces.iter().map(|f| f["id"].as_u64().unwrap()).collect();
    assert_eq!(ids, [2, 5]);
    let m = &faces[1]["material"];
    assert_eq!(m["name"], "glass");
    assert_eq!(m["diffuse"], serde_json::json!([0.1, 0.2, 0.3]));
    assert_eq!(m["emissive"], serde_json::json!([0.0, 0.5, 0.0]));
    assert_eq!(m["transparency"], 0.25);
    assert_eq!(m["two_sided"], true);
    assert_eq!(faces[1]["draw_order"], serde_json::json!([0, 2]));
    assert_eq!(faces[0]["draw_order"], serde_json::json!([1]));
    let regions = faces[1]["regions"].as_array().unwrap();
    assert_eq!(regions.len(), 2);
    assert_eq!(
        regions[1].as_array().unwrap().len(),
        2,
        "outer ring and hole"
    );
    assert_eq!(regions[1][1][0], serde_json::json!([4.5, 4.5]));
    // -0 is written as 0.
    assert!(!text.contains("-0.0"));
    assert_eq!(v["stats"]["faces_drawn"], 3);
    assert_eq!(v["stats"]["method"], "test");
}

/// The numbers of every `"regions"` array of a JSON text, one list per array, parsed with
/// Rust's correctly rounded `str::parse` (serde_json's default float parser is not: it can be
/// one ulp off without its `float_roundtrip` feature).
fn region_numbers(text: &str) -> Vec<Vec<f64>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("\"regions\": ") {
        rest = &rest[at + "\"regions\": ".len()..];
        let mut depth = 0;
        let end = rest
            .char_indices()
            .find(|&(_, c)| {
                depth += match c {
                    '[' => 1,
                    ']' => -1,
                    _ => 0,
                };
                depth == 0
            })
            .unwrap()
            .0;
        out.push(
            rest[..end]
                .split(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
                .filter(|s| !s.is_empty())
                .map(|s| s.parse().unwrap())
                .collect(),
        );
        rest = &rest[end..];
    }
    out
}

#[test]
fn json_coordinates_round_trip_exactly() {
    let scene = fixture("primitives.x3d");
    let cam = spec_camera(&scene, (333, 217));
    let screen = prepare(&scene, &cam, CullMode::Auto).screen;
    let r = painter_drawing(&scene, &screen, &cam, Fill::Shade);
    let text = write_json(&r.drawing, &scene, &r.stats);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let numbers = region_numbers(&text);
    let faces = v["faces"].as_array().unwrap();
    assert_eq!(numbers.len(), faces.len());
    let mut seen = 0;
    for (f, nums) in faces.iter().zip(&numbers) {
        let want: Vec<f64> = f["draw_order"]
            .as_array()
            .unwrap()
            .iter()
            .map(|k| &r.drawing.items[k.as_u64().unwrap() as usize])
            .inspect(|it| assert_eq!(it.face as u64, f["id"].as_u64().unwrap()))
            .inspect(|_| seen += 1)
            .flat_map(|it| it.rings.iter().flatten().flatten().map(|x| x + 0.0))
            .collect();
        assert_eq!(nums.len(), want.len());
        for (a, b) in nums.iter().zip(&want) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
        }
    }
    assert_eq!(seen, r.drawing.items.len());
    assert!(seen > 100);
}

// ---------------------------------------------------------------------------------------------
// Rasterizing drawings

#[test]
fn raster_square_with_hole_and_later_items_on_top() {
    let d = holed_drawing();
    let ids = face_ids(&d);
    let at = |i: usize, j: usize| ids[j * 12 + i];
    assert_eq!(at(0, 0), None); // outside both
    assert_eq!(at(2, 2), Some(8)); // the blue square
    assert_eq!(at(5, 5), Some(3)); // in the hole: the red strip below shows
    assert_eq!(at(6, 2), Some(8));
    assert_eq!(at(5, 9), Some(8));
    assert_eq!(at(0, 6), Some(3)); // the strip outside the square
    assert_eq!(at(2, 6), Some(8)); // the square over the strip
    assert_eq!(at(6, 3), Some(8));
    assert_eq!(at(6, 4), None); // in the hole, above the strip
    let c = colors(&d);
    let px = |i: usize, j: usize| c[j * 12 + i];
    assert_eq!(px(0, 0), [1.0, 1.0, 1.0]);
    assert_eq!(px(5, 4), [1.0, 1.0, 1.0]);
    assert_eq!(px(5, 5), [1.0, 0.0, 0.0]);
    assert_eq!(px(2, 2), [0.5, 0.5, 1.0]); // half blue over white
    assert_eq!(px(2, 6), [0.5, 0.0, 0.5]); // half blue over red

    // Reversing the order puts the strip on top.
    let mut r = d.clone();
    r.items.reverse();
    assert_eq!(face_ids(&r)[6 * 12 + 2], Some(3));
}

#[test]
fn seed_transparent_scene_blends_exactly() {
    check_seed_transparent(&Painter);
}

#[test]
fn seed_transparent_scene_blends_exactly_with_the_exact_strategies() {
    for (_, strategy) in exact_strategies() {
        check_seed_transparent(strategy);
    }
}

fn check_seed_transparent(strategy: &dyn Strategy) {
    let scene = fixture("seed_transparent.x3d");
    let cam = scene_camera(&scene);
    let screen = prepare(&scene, &cam, CullMode::Auto).screen;
    let mut r = drawing_of(
        strategy,
        &scene,
        &screen,
        &cam,
        Fill::Shade,
        sightline::draw::DrawOptions::per_face(),
    );
    r.drawing.background = Some([0.0; 3]);
    assert_eq!(r.drawing.items.len(), 2);
    assert_eq!(
        r.drawing.items[1].opacity, 0.6,
        "green, in front, drawn last"
    );
    assert_seed_transparent_colours(&colors(&r.drawing), &cam);
}

// ---------------------------------------------------------------------------------------------
// Painter against the z-buffer

/// Interior pixels (3x3 neighbourhood of one id in the z-buffer image) where the painter's
/// drawing shows another face, and the number of interior pixels.
fn painter_mismatches(scene: &Scene, cam: &Camera) -> (usize, usize) {
    let (prepared, zb) = render_zbuffer(scene, cam, CullMode::Auto, |_| {});
    let reference = zb.face_ids(&prepared.screen);
    let r = painter_drawing(scene, &prepared.screen, cam, Fill::Id);
    assert_eq!(r.drawing.items.len(), prepared.screen.polys.len());
    assert_eq!(r.stats["faces_drawn"], prepared.screen.polys.len());
    let ids = face_ids(&r.drawing);
    let (w, h) = (cam.width as usize, cam.height as usize);
    let (interior, bad) = interior_mismatches(&reference, &ids, w, h);
    (bad.len(), interior.len())
}

#[test]
fn painter_matches_the_zbuffer_on_the_seed_scene() {
    let scene = fixture("seed_two_triangles.x3d");
    let (bad, interior) = painter_mismatches(&scene, &scene_camera(&scene));
    assert_eq!(bad, 0);
    assert!(interior > 500_000);
}

#[test]
fn painter_misorders_a_long_face_on_the_primitives() {
    // No cyclic overlap here, yet the farthest-corner sort is wrong: the box is 4 units deep, so
    // its side facing the sphere has its farthest corner behind every sphere face and is drawn
    // first, though it covers some of them. Every mismatch is that face hidden by the sphere.
    let scene = fixture("primitives.x3d");
    let cam = spec_camera(&scene, (640, 480));
    let (prepared, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
    let reference = zb.face_ids(&prepared.screen);
    let r = painter_drawing(&scene, &prepared.screen, &cam, Fill::Id);
    let ids = face_ids(&r.drawing);
    let mesh_of = |id: u32| {
        let f = scene.faces.iter().find(|f| f.id == id).unwrap();
        scene.meshes[f.mesh as usize].name.as_str()
    };
    let (interior, bad) = interior_mismatches(&reference, &ids, 640, 480);
    assert!(!bad.is_empty());
    assert!(
        bad.len() * 1000 < interior.len(),
        "{} of {}",
        bad.len(),
        interior.len()
    );
    let box_face = bad[0].2.unwrap();
    let deepest = |id: u32| {
        prepared
            .screen
            .polys
            .iter()
            .filter(|p| p.id == id)
            .flat_map(|p| prepared.screen.corners(p))
            .map(|q| q.z)
            .max()
            .unwrap()
    };
    for &(_, _, z, p) in &bad {
        let (z, p) = (z.unwrap(), p.unwrap());
        assert_eq!(z, box_face);
        assert_eq!((mesh_of(z), mesh_of(p)), ("box", "sphere"));
        assert!(deepest(z) > deepest(p), "the box face sorts behind");
    }
}

#[test]
fn painter_matches_the_zbuffer_on_a_100k_triangle_sphere_at_1024() {
    // A convex closed mesh: after culling nothing overlaps, so any order is right; this checks
    // the rings and the rasterizer at scale (and that they are fast enough).
    let scene = sphere_scene(200_000);
    let cam = spec_camera(&scene, (1024, 1024));
    let t = std::time::Instant::now();
    let (bad, interior) = painter_mismatches(&scene, &cam);
    assert_eq!(bad, 0, "of {interior} interior pixels");
    assert!(interior > 300_000);
    eprintln!("sphere: {:?}", t.elapsed());
}

#[test]
fn painter_fails_on_cyclic_overlap() {
    // Three bars along the sides of a triangle, each rising from its start to its end: at every
    // corner the bar arriving is above the bar leaving, so 0 is over 1 over 2 over 0.
    let mut b = SceneBuilder::new("cyclic");
    let corner = |k: usize| {
        let a = std::f64::consts::FRAC_PI_2 + k as f64 * 2.0 * std::f64::consts::PI / 3.0;
        DVec3::new(a.cos(), a.sin(), 0.0)
    };
    for k in 0..3 {
        let (p, q) = (corner(k), corner((k + 1) % 3));
        let along = q - p;
        let side = DVec3::new(-along.y, along.x, 0.0).normalize() * 0.15;
        let at = |t: f64, s: f64| p + along * t + side * s + DVec3::new(0.0, 0.0, t - 0.5);
        b.begin_mesh(format!("bar{k}"));
        let m = b.default_material();
        let v: Vec<u32> = [(-0.3, -1.0), (1.3, -1.0), (1.3, 1.0), (-0.3, 1.0)]
            .iter()
            .map(|&(t, s)| b.add_vertex(at(t, s)))
            .collect();
        b.add_face(&v, m);
    }
    let scene = b.finish().unwrap();
    let cam = ortho_down_z(10.0, 3.5, (160, 160));
    let (bad, interior) = painter_mismatches(&scene, &cam);
    assert!(
        bad > 0,
        "the painter cannot order a cycle ({interior} interior)"
    );
}

#[test]
fn painter_fails_on_interpenetrating_triangles() {
    let mut b = SceneBuilder::new("pierce");
    let p = |x, y, z| DVec3::new(x, y, z);
    add_triangle(
        &mut b,
        [p(-1.0, -1.0, 0.0), p(1.0, -1.0, 0.0), p(0.0, 1.0, 0.0)],
    );
    add_triangle(
        &mut b,
        [p(-0.9, -1.0, -0.5), p(1.1, -1.0, -0.5), p(0.1, 1.0, 0.5)],
    );
    let scene = b.finish().unwrap();
    let cam = ortho_down_z(10.0, 2.5, (128, 128));
    let (bad, interior) = painter_mismatches(&scene, &cam);
    assert!(bad > 100, "{bad} of {interior}");
}

#[test]
fn the_method_list_has_the_painter_marked_approximate() {
    assert!(METHODS.iter().any(|m| m.name == "painter" && !m.exact));
    assert!(method("painter").is_some());
    assert!(method("nope").is_none());
}

/// A flat face stored as a fan of triangles (as CAD exports do), next to a tilted triangle of the
/// same material and a coplanar triangle of another colour: with surface merging the fan is one
/// SVG path listing all its faces, the others stay apart, and JSON (never merged) keeps one
/// entry per face; the face ids at pixel centres are the same either way.
#[test]
fn coplanar_faces_of_one_paint_are_drawn_as_one_region() {
    let mut b = SceneBuilder::new("fan");
    b.begin_mesh("fan");
    let m = b.default_material();
    let red = b.add_material(Material {
        name: "red".into(),
        diffuse: [1.0, 0.0, 0.0],
        ..Material::default()
    });
    // A hexagon in z = 0 as six triangles around its centre (ids 0..6).
    let c = b.add_vertex(DVec3::ZERO);
    let ring: Vec<u32> = (0..6)
        .map(|k| {
            let a = std::f64::consts::PI / 3.0 * k as f64;
            b.add_vertex(DVec3::new(a.cos(), a.sin(), 0.0))
        })
        .collect();
    for k in 0..6 {
        b.add_face(&[c, ring[k], ring[(k + 1) % 6]], m);
    }
    // Same plane, other colour (id 6); tilted, same material (id 7).
    let p = [(1.2, 0.0), (2.2, 0.0), (1.7, 0.8)].map(|(x, y)| b.add_vertex(DVec3::new(x, y, 0.0)));
    b.add_face(&p, red);
    let t = [(-1.2, 0.0, 0.0), (-2.2, 0.0, 0.3), (-1.7, 0.8, 0.0)]
        .map(|(x, y, z)| b.add_vertex(DVec3::new(x, y, z)));
    b.add_face(&t, m);
    let scene = b.finish().unwrap();
    let cam = front_ortho(3.0, 160, 100);
    let screen = prepare(&scene, &cam, CullMode::Off).screen;
    let merged = drawing_of(
        &CoverageMap,
        &scene,
        &screen,
        &cam,
        Fill::Shade,
        sightline::draw::DrawOptions {
            merge_surfaces: true,
            seams: false,
            background: None,
        },
    );
    let apart = exact_drawing(&scene, &screen, &cam, Fill::Shade);
    let svg = write_svg(&merged.drawing, &SvgOptions::default());
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let faces: Vec<Option<&str>> = svg_paths(&doc)
        .iter()
        .map(|p| p.attribute("data-faces"))
        .collect();
    assert_eq!(faces.len(), 3, "{svg}");
    assert_eq!(
        faces.iter().flatten().collect::<Vec<_>>(),
        vec![&"0 1 2 3 4 5"],
        "{svg}"
    );
    assert_eq!(apart.drawing.items.len(), 8);
    assert!(apart.drawing.items.iter().all(|it| it.merged.is_empty()));
    assert_eq!(
        face_ids(&merged.drawing)
            .iter()
            .map(|f| f.is_some())
            .collect::<Vec<_>>(),
        face_ids(&apart.drawing)
            .iter()
            .map(|f| f.is_some())
            .collect::<Vec<_>>(),
        "merging changes no coverage"
    );
    let json = write_json(&apart.drawing, &scene, &apart.stats);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["faces"].as_array().unwrap().len(), 8);
}

/// A translucent scene's drawing (the opaque faces' visible set, then the translucent parts in
/// front of it, back to front) blends to the A-buffer's colours at pixel centres: nothing hidden
/// behind an opaque face shows, nothing blends twice. Random two-sided triangles, every other
/// one translucent; a pixel on a region edge may differ (the drawing's vertices are rounded,
/// the A-buffer samples exactly), under 0.1 %.
#[test]
fn translucent_drawings_blend_as_the_abuffer_does() {
    use sightline::paint::to_u8;
    use sightline::raster::abuffer;
    for seed in 1..=4 {
        let mut scene = random_triangles(40, seed);
        let mut glass = scene.materials[0].clone();
        glass.transparency = 0.5;
        glass.diffuse = [0.2, 0.5, 0.9];
        scene.materials.push(glass);
        let glass = scene.materials.len() as u32 - 1;
        for f in scene.faces.iter_mut().step_by(2) {
            f.material = glass;
        }
        let cam = spec_camera(&scene, (160, 120));
        let screen = prepare(&scene, &cam, CullMode::Auto).screen;
        let mut drawing = exact_drawing(&scene, &screen, &cam, Fill::Shade).drawing;
        assert!(drawing.items.iter().any(|i| i.opacity < 1.0));
        drawing.background = Some([1.0; 3]);
        let ours = colors(&drawing);
        let paints = sightline::paint::screen_paints(&scene, &screen, &cam, Fill::Shade);
        let reference = abuffer::render(&screen, &paints, [1.0; 3], abuffer::Options::default());
        let differ = ours
            .iter()
            .zip(&reference.color)
            .filter(|(a, b)| {
                let (a, b) = (to_u8(**a), to_u8(**b));
                (0..3).any(|c| a[c].abs_diff(b[c]) > 2)
            })
            .count();
        // 0 on these seeds; drawing nothing of the translucent parts' clipping differs on 1.2 %.
        assert!(
            differ * 1000 < ours.len(),
            "seed {seed}: {differ} of {} pixels differ from the A-buffer",
            ours.len()
        );
    }
}
