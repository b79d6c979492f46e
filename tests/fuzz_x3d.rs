//! The X3D loader never panics: random bytes, mutations of the good fixtures (byte flips,
//! insertions, deletions, truncation, chunk duplication, attribute values replaced by random
//! numbers or garbage) and random well-formed scenes either load into a scene that keeps the
//! scene invariants or give an error located at an element.
//!
//! The default case counts keep `cargo test --release` quick; the `#[ignore]`d `long_*` tests
//! take their case count from `SIGHTLINE_FUZZ_CASES` (default 100 000):
//! `SIGHTLINE_FUZZ_CASES=1000000 cargo test --release --test fuzz_x3d -- --ignored --nocapture`.
//! Each run prints how many cases loaded and how many were refused; `SIGHTLINE_FUZZ_VERBOSE=1`
//! prints every refusal, to see which layer the cases reach.

mod support;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use sightline::Location;
use sightline::scene::{Format, load_bytes};
use std::cell::Cell;
use std::time::Instant;
use support::fixtures::{assert_corner_attributes, fixtures_dir};
use support::rng::cases_from_env;

const FIXTURES: &[&str] = &[
    include_str!("../fixtures/seed_two_triangles.x3d"),
    include_str!("../fixtures/seed_transparent.x3d"),
    include_str!("../fixtures/primitives.x3d"),
    include_str!("../fixtures/indexed.x3d"),
    include_str!("../fixtures/checker_quad.x3d"),
];

thread_local! {
    /// Outcomes in this test's thread: (loaded, refused).
    static OUTCOMES: Cell<(usize, usize)> = const { Cell::new((0, 0)) };
}

/// Loads and checks the outcome: a scene keeps its invariants, an error names an element.
fn check(bytes: &[u8]) {
    // ImageTexture urls are resolved against the fixtures (only checked for existence).
    match load_bytes(bytes, Format::X3d, "fuzz.x3d", Some(&fixtures_dir())) {
        Ok(s) => {
            OUTCOMES.set((OUTCOMES.get().0 + 1, OUTCOMES.get().1));
            assert!(!s.faces.is_empty());
            assert_corner_attributes(&s);
            assert!(s.material_textures.len() <= s.materials.len());
            assert!(s.positions.iter().all(|p| p.is_finite()));
            for f in &s.faces {
                assert!(f.len >= 3);
                assert!((f.material as usize) < s.materials.len());
                assert!((f.mesh as usize) < s.meshes.len());
                assert!(f.id < s.input_faces);
                assert!(
                    s.face_corners(f)
                        .iter()
                        .all(|&c| (c as usize) < s.positions.len())
                );
            }
            for m in &s.meshes {
                assert!(m.faces.end <= s.faces.len() && !m.faces.is_empty());
            }
            for m in &s.materials {
                let colours = m.diffuse.iter().chain(&m.emissive).chain([&m.transparency]);
                assert!(colours.into_iter().all(|c| (0.0..=1.0).contains(c)));
            }
            if let Some(v) = s.viewpoint {
                assert!(v.position.is_finite() && v.orientation_axis.is_finite());
                assert!(v.orientation_angle.is_finite());
                assert!(v.field_of_view > 0.0 && v.field_of_view < std::f64::consts::PI);
            }
        }
        Err(e) => {
            if std::env::var_os("SIGHTLINE_FUZZ_VERBOSE").is_some() {
                println!("refused: {e}");
            }
            OUTCOMES.set((OUTCOMES.get().0, OUTCOMES.get().1 + 1));
            assert_eq!(e.file, "fuzz.x3d");
            assert!(!e.message.is_empty());
            match e.location {
                Location::Element { name, line } => {
                    assert!(line >= 1 && !name.is_empty(), "{name} {line}");
                }
                other => panic!("X3D error not at an element: {other:?}"),
            }
        }
    }
}

#[derive(Clone, Debug)]
enum Mutation {
    Flip { at: usize, bit: u8 },
    Insert { at: usize, bytes: Vec<u8> },
    Delete { at: usize, len: usize },
    Truncate { at: usize },
    Duplicate { from: usize, len: usize, to: usize },
    Attribute { which: usize, value: String },
}

/// Pieces of X3D worth inserting: tags, references, numbers at the edges.
const TOKENS: &[&str] = &[
    "<",
    ">",
    "/>",
    "</",
    "\"",
    "'",
    " -1",
    " 0",
    " 1e308",
    " -1e308",
    " NaN",
    " inf",
    "&amp;",
    "&bogus;",
    "<!--",
    "-->",
    "<![CDATA[x]]>",
    "<Group>",
    "</Group>",
    "<Transform scale='1e300 1e300 1e300'>",
    "<Transform rotation='0 0 0 1'>",
    "</Transform>",
    "<Shape><Box/></Shape>",
    "<Shape USE='box'/>",
    "<Group USE='tetra'/>",
    " DEF='box'",
    " USE='floorPoints'",
    "<Viewpoint fieldOfView='3.2'/>",
    "<Coordinate point='0 0 0 1 1 1'/>",
    "<IndexedFaceSet coordIndex='0 0 0 -1 -1'>",
    "<TextureCoordinate point='0 0 1 0 1 1'/>",
    "<Normal vector='0 0 1'/>",
    "<ImageTexture url='\"checker16.png\"'/>",
    " texCoordIndex='0 1 2 -1'",
    " normalIndex='0 0 0 -1'",
    " normalPerVertex='false'",
    " url='\"a\" \"'",
    "\u{feff}",
    "\u{00e9}",
];

fn number() -> BoxedStrategy<String> {
    prop_oneof![
        any::<f64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        (-3i64..12).prop_map(|x| x.to_string()),
        (-1.0e3f64..1.0e3).prop_map(|x| format!("{x:e}")),
        Just("1e-320".to_string()),
        Just("-0".to_string()),
        Just("0x7fffffff".to_string()),
    ]
    .boxed()
}

fn attribute_value() -> BoxedStrategy<String> {
    let moderate = |n: std::ops::Range<usize>| {
        prop::collection::vec(-10.0f64..10.0, n).prop_map(|v| {
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        })
    };
    prop_oneof![
        // Well-shaped values: whole points, one number, a rotation.
        3 => (1usize..10).prop_flat_map(move |k| moderate(3 * k..3 * k + 1)),
        1 => moderate(1..2),
        1 => moderate(4..5),
        2 => prop::collection::vec(number(), 0..24).prop_map(|v| v.join(" ")),
        1 => prop::collection::vec(number(), 0..8).prop_map(|v| v.join(", ")),
        1 => "[ -~]{0,40}",
        1 => any::<String>(),
        1 => Just(String::new()),
        1 => Just("true".to_string()),
        1 => Just("false".to_string()),
    ]
    .boxed()
}

/// Mostly a valid value of `n` numbers in `range`, sometimes anything.
fn mostly_valid(n: usize, lo: f64, hi: f64) -> BoxedStrategy<String> {
    prop_oneof![
        30 => prop::collection::vec(lo..hi, n).prop_map(|v| {
            v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ")
        }),
        1 => attribute_value(),
    ]
    .boxed()
}

fn mutation() -> impl Strategy<Value = Mutation> {
    // Attribute replacements are weighted up: byte-level damage mostly exercises the XML
    // parser, replaced values reach the X3D reader behind it.
    prop_oneof![
        1 => (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        2 => (
            any::<usize>(),
            prop_oneof![
                prop::collection::vec(any::<u8>(), 1..8),
                prop::sample::select(TOKENS).prop_map(|t| t.as_bytes().to_vec()),
            ]
        )
            .prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
        1 => (any::<usize>(), 1usize..64).prop_map(|(at, len)| Mutation::Delete { at, len }),
        1 => any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        1 => (any::<usize>(), 1usize..400, any::<usize>())
            .prop_map(|(from, len, to)| Mutation::Duplicate { from, len, to }),
        8 => (any::<usize>(), attribute_value())
            .prop_map(|(which, value)| Mutation::Attribute { which, value }),
    ]
}

/// Byte ranges of the attribute values (inside their quotes).
fn attribute_values(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < bytes.len() {
        if bytes[i] == b'=' {
            let mut j = i + 1;
            while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                j += 1;
            }
            if j < bytes.len() && (bytes[j] == b'"' || bytes[j] == b'\'') {
                let q = bytes[j];
                if let Some(k) = bytes[j + 1..].iter().position(|&c| c == q) {
                    out.push((j + 1, j + 1 + k));
                    i = j + 1 + k;
                }
            }
        }
        i += 1;
    }
    out
}

fn apply(mut bytes: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let n = bytes.len();
        match m {
            Mutation::Flip { at, bit } => {
                if n > 0 {
                    bytes[at % n] ^= 1 << bit;
                }
            }
            Mutation::Insert { at, bytes: b } => {
                let at = at % (n + 1);
                bytes.splice(at..at, b.iter().copied());
            }
            Mutation::Delete { at, len } => {
                let at = at % (n + 1);
                bytes.drain(at..(at + len).min(n));
            }
            Mutation::Truncate { at } => bytes.truncate(at % (n + 1)),
            Mutation::Duplicate { from, len, to } => {
                let from = from % (n + 1);
                let chunk = bytes[from..(from + len).min(n)].to_vec();
                let to = to % (n + 1);
                bytes.splice(to..to, chunk);
            }
            Mutation::Attribute { which, value } => {
                let spans = attribute_values(&bytes);
                if !spans.is_empty() {
                    let (a, b) = spans[which % spans.len()];
                    let quoted = value.replace(['"', '\''], "");
                    bytes.splice(a..b, quoted.bytes());
                }
            }
        }
    }
    bytes
}

fn mutated_fixture() -> impl Strategy<Value = Vec<u8>> {
    (
        prop::sample::select(FIXTURES),
        prop::collection::vec(mutation(), 1..4),
    )
        .prop_map(|(f, ms)| apply(f.as_bytes().to_vec(), &ms))
}

fn random_bytes() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        prop::collection::vec(any::<u8>(), 0..512),
        // Bytes from an XML-ish alphabet reach the parser's deeper states.
        prop::collection::vec(
            prop::sample::select(b"<>/='\" \nScenShapeBoxX3D-1.0e".to_vec()),
            0..512
        ),
    ]
}

/// A random well-formed scene: nested transforms around shapes with random polygons, many of
/// them degenerate, non-planar or self-intersecting, to exercise the builder through the loader.
fn random_scene() -> impl Strategy<Value = Vec<u8>> {
    let coord = prop_oneof![
        (-4i32..5).prop_map(|x| x.to_string()),
        (-1.0e3f64..1.0e3).prop_map(|x| x.to_string()),
        any::<f64>()
            .prop_filter("finite", |x| x.is_finite())
            .prop_map(|x| x.to_string()),
    ];
    let points = prop::collection::vec(coord, 3..60);
    let index = prop::collection::vec(-1i32..20, 0..80);
    // Optional TextureCoordinate / Normal children with their own index lists: (how many
    // values, own index list or none (the coordIndex rule), per vertex).
    let attributes = (
        prop::option::of((
            1usize..12,
            prop::option::of(prop::collection::vec(-1i32..12, 0..80)),
        )),
        prop::option::of((
            1usize..12,
            prop::option::of(prop::collection::vec(-1i32..12, 0..80)),
        )),
        any::<bool>(),
        any::<bool>(),
    );
    let shape = (
        0usize..8,
        points,
        index,
        mostly_valid(1, 0.0, 3.0),
        mostly_valid(3, 0.0, 1.0),
        any::<bool>(),
        any::<bool>(),
        attributes,
    )
        .prop_map(|(kind, mut pts, index, value, colour, ccw, solid, (tex, nor, per_vertex, texture))| {
            pts.truncate(pts.len() / 3 * 3);
            let n = (pts.len() / 3) as i32;
            let pts = pts.join(" ");
            // Mostly in range: the bad-index errors are the mutation tests' business.
            let idx: Vec<String> = index
                .iter()
                .map(|&i| if i < 0 { i } else { i % n }.to_string())
                .collect();
            let idx = idx.join(" ");
            let mut flags = format!("ccw='{ccw}' solid='{solid}' normalPerVertex='{per_vertex}'");
            // Mostly the coordIndex structure with in-range values, sometimes anything.
            let own_index = |own: &Option<Vec<i32>>, count: usize| match own {
                Some(v) if v.len() % 3 == 0 => Some(
                    v.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" "),
                ),
                _ => Some(
                    index
                        .iter()
                        .zip(own.iter().flatten().chain(std::iter::repeat(&0)))
                        .map(|(&i, &o)| if i < 0 { -1 } else { o.rem_euclid(count as i32) })
                        .map(|i| i.to_string())
                        .collect::<Vec<_>>()
                        .join(" "),
                )
                .filter(|_| own.is_some()),
            };
            let mut children = String::new();
            // Large counts stand for "one per point", so that many cases load.
            let fit = |c: usize| if c >= 8 { (n as usize).max(1) } else { c };
            // (element, its field, numbers per value, values cycle below, the index attribute)
            for (attribute, element, field, width, cycle, index_name) in [
                (&tex, "TextureCoordinate", "point", 2, 3, "texCoordIndex"),
                (&nor, "Normal", "vector", 3, 4, "normalIndex"),
            ] {
                if let Some((count, own)) = attribute {
                    let count = fit(*count);
                    let v: Vec<String> =
                        (0..width * count).map(|k| (k % cycle).to_string()).collect();
                    children += &format!("<{element} {field}='{}'/>", v.join(" "));
                    if let Some(i) = own_index(own, count) {
                        flags += &format!(" {index_name}='{i}'");
                    }
                }
            }
            let image = if texture { "<ImageTexture url='\"checker16.png\"'/>" } else { "" };
            let value = value.replace(['"', '\'', '<', '&'], "");
            let colour = colour.replace(['"', '\'', '<', '&'], "");
            let geometry = match kind {
                0 => format!("<TriangleSet {flags}><Coordinate point='{pts}'/>{children}</TriangleSet>"),
                1 | 2 => format!(
                    "<IndexedFaceSet {flags} coordIndex='{idx}'><Coordinate point='{pts}'/>{children}</IndexedFaceSet>"
                ),
                3 => {
                    // No separators in an IndexedTriangleSet.
                    let idx = idx.replace("-1", "0");
                    format!(
                        "<IndexedTriangleSet {flags} index='{idx}'><Coordinate point='{pts}'/>{children}</IndexedTriangleSet>"
                    )
                }
                4 => format!("<Box size='{value} {value} {value}'/>"),
                5 => format!("<Sphere radius='{value}'/>"),
                6 => format!("<Cone bottomRadius='{value}' side='{ccw}' bottom='{solid}'/>"),
                _ => format!("<Cylinder height='{value}' top='{ccw}'/>"),
            };
            format!("<Shape><Appearance><Material diffuseColor='{colour}'/>{image}</Appearance>{geometry}</Shape>")
        });
    let transform = (
        prop::option::of(mostly_valid(3, -3.0, 3.0)),
        prop::option::of(mostly_valid(4, -1.0, 7.0)),
        prop::option::of(mostly_valid(3, -2.0, 2.0)),
        prop::option::of(mostly_valid(3, -1.0, 1.0)),
        prop::option::of(mostly_valid(4, -1.0, 7.0)),
        prop::option::of(mostly_valid(4, -1.0, 7.0)),
    )
        .prop_map(|(t, r, s, c, so, view)| {
            let mut tag = String::from("<Transform");
            let fields = [
                ("translation", t),
                ("rotation", r),
                ("scale", s),
                ("center", c),
                ("scaleOrientation", so),
            ];
            for (name, value) in fields {
                if let Some(v) = value {
                    let v = v.replace(['"', '\'', '<', '&'], "");
                    tag.push_str(&format!(" {name}='{v}'"));
                }
            }
            tag.push('>');
            if let Some(v) = view {
                let v = v.replace(['"', '\'', '<', '&'], "");
                tag.push_str(&format!("<Viewpoint orientation='{v}'/>"));
            }
            tag
        });
    prop::collection::vec((prop::collection::vec(transform, 0..4), shape), 1..5).prop_map(|items| {
        let mut s = String::from("<X3D><Scene>");
        for (transforms, shape) in items {
            for t in &transforms {
                s.push_str(t);
            }
            s.push_str(&shape);
            s.push_str(&"</Transform>".repeat(transforms.len()));
        }
        s.push_str("</Scene></X3D>");
        s.into_bytes()
    })
}

/// Runs `cases` cases and prints how many loaded and how many were refused (`--nocapture`).
fn run<S: Strategy<Value = Vec<u8>>>(name: &str, cases: u32, strategy: S) {
    OUTCOMES.set((0, 0));
    let start = Instant::now();
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new(config);
    let result = runner.run(&strategy, |bytes| {
        check(&bytes);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let (loaded, refused) = OUTCOMES.get();
    println!(
        "{name}: {cases} cases in {:.1} s: {loaded} loaded, {refused} refused",
        start.elapsed().as_secs_f64()
    );
}

fn long_cases() -> u32 {
    cases_from_env("SIGHTLINE_FUZZ_CASES", 100_000)
}

#[test]
fn fuzz_random_bytes() {
    run("random_bytes", 5000, random_bytes());
}

#[test]
fn fuzz_mutated_fixtures() {
    run("mutated_fixtures", 10_000, mutated_fixture());
}

#[test]
fn fuzz_random_scenes() {
    run("random_scenes", 4000, random_scene());
}

#[test]
#[ignore]
fn long_fuzz_random_bytes() {
    run("long random_bytes", long_cases(), random_bytes());
}

#[test]
#[ignore]
fn long_fuzz_mutated_fixtures() {
    run("long mutated_fixtures", long_cases(), mutated_fixture());
}

#[test]
#[ignore]
fn long_fuzz_random_scenes() {
    run("long random_scenes", long_cases(), random_scene());
}

#[test]
fn mutations_apply_where_intended() {
    let text = b"<a x='1 2' y=\"3\"/>".to_vec();
    assert_eq!(attribute_values(&text), vec![(6, 9), (14, 15)]);
    let out = apply(
        text,
        &[Mutation::Attribute {
            which: 1,
            value: "NaN".into(),
        }],
    );
    assert_eq!(out, b"<a x='1 2' y=\"NaN\"/>");
}
