//! The OBJ, STL and PLY loaders never panic: on random bytes, on token soups of each format's
//! keywords and troublesome numbers, on structurally valid files with random contents, and on
//! random mutations (bit flips, byte and token insertions, deletions, duplications, truncation) of
//! the good and bad fixtures. MTL files are fuzzed through an OBJ that references them.
//!
//! The default tests run a modest number of cases. The `#[ignore]`d `*_long` ones run
//! `SIGHTLINE_FUZZ_CASES` cases (default 1,000,000) per format, a tenth of that for MTL:
//! `SIGHTLINE_FUZZ_CASES=200000 cargo test --release --test fuzz_mesh_formats -- --ignored`.

mod support;

use proptest::prelude::*;
use proptest::sample::{Index, select};
use proptest::test_runner::{Config, TestRunner};
use sightline::scene::{Format, load_bytes};
use std::cell::Cell;
use std::time::Instant;
use support::fixtures::{assert_corner_attributes, fixtures_dir};
use support::rng::cases_from_env;

const DEFAULT_CASES: u32 = 100_000;

fn seeds(format: Format) -> Vec<Vec<u8>> {
    let ext = match format {
        Format::Obj => "obj",
        Format::Stl => "stl",
        Format::Ply => "ply",
        Format::X3d => "x3d",
    };
    let mut out = Vec::new();
    // The good fixtures three times: mutants of them get further than mutants of broken files.
    for dir in [
        fixtures_dir(),
        fixtures_dir(),
        fixtures_dir(),
        fixtures_dir().join("bad"),
    ] {
        let mut paths: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.extension()
                    .is_some_and(|e| e == ext || (format == Format::Obj && e == "mtl"))
            })
            .collect();
        paths.sort();
        out.extend(paths.iter().map(|p| std::fs::read(p).unwrap()));
    }
    assert!(out.len() >= 5, "too few {ext} seeds");
    out.extend(grid_seeds(format));
    out
}

/// A bumpy 6 x 6 grid of quads (non-planar ones among them) in the given format: seeds whose
/// bytes are mostly body, so that mutations land in vertex and face data.
fn grid_seeds(format: Format) -> Vec<Vec<u8>> {
    const N: usize = 7;
    let verts: Vec<[f64; 3]> = (0..N * N)
        .map(|k| [(k % N) as f64, (k / N) as f64, ((k * 7) % 3) as f64 * 0.25])
        .collect();
    let quads: Vec<[usize; 4]> = (0..(N - 1) * (N - 1))
        .map(|k| {
            let (i, j) = (k % (N - 1), k / (N - 1));
            let a = j * N + i;
            [a, a + 1, a + N + 1, a + N]
        })
        .collect();
    let tris: Vec<[[f64; 3]; 3]> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .map(|t| t.map(|i| verts[i]))
        .collect();
    match format {
        Format::Obj => {
            let mut s = String::from("o grid\n");
            for v in &verts {
                s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
            }
            // What the odd faces' `/1` and `//2` refer to.
            s += "vt 0 0\nvt 1 0 0\nvn 0 0 1\nvn 0.1 0 1\n";
            for (k, q) in quads.iter().enumerate() {
                let n = verts.len() as i64;
                let r = |i: usize| i as i64 - n;
                match k % 4 {
                    0 | 2 => {
                        s += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1)
                    }
                    // Every corner with both attributes: they reach the builder.
                    1 => {
                        s += &format!(
                            "f {}/1/1 {}/2/2 {}/-1/1 {}/-2/-1\n",
                            q[0] + 1,
                            r(q[1]),
                            q[2] + 1,
                            r(q[3])
                        )
                    }
                    // Attributes on some corners only: the face gets none.
                    _ => {
                        s += &format!("f {}/1 {}/1 {}//2 {}\n", r(q[0]), r(q[1]), r(q[2]), r(q[3]))
                    }
                }
            }
            vec![s.into_bytes()]
        }
        Format::Stl => {
            let mut s = String::from("solid grid\n");
            for t in &tris {
                s += "facet normal 0 0 1\nouter loop\n";
                for v in t {
                    s += &format!("vertex {} {} {}\n", v[0], v[1], v[2]);
                }
                s += "endloop\nendfacet\n";
            }
            s += "endsolid grid\n";
            vec![
                s.into_bytes(),
                support::generated::binary_stl("grid", &tris),
            ]
        }
        Format::Ply => {
            let head = |fmt: &str| {
                format!(
                    "ply\nformat {fmt} 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
                    verts.len(),
                    quads.len()
                )
                .into_bytes()
            };
            let mut ascii = head("ascii");
            for v in &verts {
                ascii.extend_from_slice(format!("{} {} {}\n", v[0], v[1], v[2]).as_bytes());
            }
            for q in &quads {
                ascii.extend_from_slice(
                    format!("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]).as_bytes(),
                );
            }
            let mut out = vec![ascii];
            for be in [false, true] {
                let mut b = head(if be {
                    "binary_big_endian"
                } else {
                    "binary_little_endian"
                });
                let mut put = |x: [u8; 4]| {
                    b.extend(if be {
                        x.iter().rev().copied().collect::<Vec<_>>()
                    } else {
                        x.to_vec()
                    })
                };
                for v in &verts {
                    for c in v {
                        put((*c as f32).to_le_bytes());
                    }
                }
                for q in &quads {
                    put_byte(&mut b, 4);
                    for i in q {
                        let x = (*i as i32).to_le_bytes();
                        b.extend(if be {
                            x.iter().rev().copied().collect::<Vec<_>>()
                        } else {
                            x.to_vec()
                        });
                    }
                }
                out.push(b);
            }
            out
        }
        Format::X3d => Vec::new(),
    }
}

fn put_byte(b: &mut Vec<u8>, x: u8) {
    b.push(x);
}

/// Tokens that exercise each parser's edges.
fn dictionary(format: Format) -> Vec<&'static [u8]> {
    let mut d: Vec<&'static [u8]> = vec![
        b" ",
        b"\n",
        b"\r\n",
        b"\t",
        b"0",
        b"1",
        b"-1",
        b"2",
        b"3",
        b"4",
        b"255",
        b"65535",
        b"4294967295",
        b"4294967296",
        b"9223372036854775807",
        b"-9223372036854775808",
        b"99999999999999999999",
        b"nan",
        b"-nan",
        b"inf",
        b"-inf",
        b"1e308",
        b"1e309",
        b"-1e308",
        b"1e-320",
        b"0.5",
        b"-0.0",
        b"1.#QNAN",
        b"\xff",
        b"\x00",
        b"#",
    ];
    match format {
        Format::Obj => d.extend_from_slice(&[
            b"v",
            b"vt",
            b"vn",
            b"f",
            b"o",
            b"g",
            b"s",
            b"l",
            b"usemtl",
            b"mtllib",
            b"newmtl",
            b"Kd",
            b"d",
            b"Tr",
            b"map_Kd",
            b"/",
            b"//",
            b"\\\n",
            b"\\",
            b"-4",
            b"-3",
            b"0/0/0",
            b"1/2/3",
            b"1/1/1",
            b"-1/-1/-1",
            b"2//2",
            b"vt 0 0\n",
            b"vn 0 0 1\n",
        ]),
        Format::Stl => d.extend_from_slice(&[
            b"solid",
            b"SOLID",
            b"facet",
            b"normal",
            b"outer",
            b"loop",
            b"vertex",
            b"endloop",
            b"endfacet",
            b"endsolid",
        ]),
        Format::Ply => d.extend_from_slice(&[
            b"ply",
            b"format",
            b"ascii",
            b"binary_little_endian",
            b"binary_big_endian",
            b"1.0",
            b"element",
            b"property",
            b"list",
            b"char",
            b"uchar",
            b"short",
            b"ushort",
            b"int",
            b"uint",
            b"float",
            b"double",
            b"int8",
            b"uint32",
            b"float64",
            b"vertex",
            b"face",
            b"x",
            b"y",
            b"z",
            b"vertex_indices",
            b"vertex_index",
            b"end_header",
            b"comment",
            b"\xff\xff\xff\xff",
            b"\x7f\xff\xff\xff",
            b"\x00\x00\x80\x7f",
        ]),
        Format::X3d => {}
    }
    d
}

#[derive(Clone, Debug)]
enum Mutation {
    FlipBit(Index, u8),
    SetByte(Index, u8),
    InsertByte(Index, u8),
    Delete(Index, u8),
    Duplicate(Index, Index),
    InsertToken(Index, Index),
    Truncate(Index),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<Index>(), 0u8..8).prop_map(|(i, b)| Mutation::FlipBit(i, b)),
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::SetByte(i, b)),
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::InsertByte(i, b)),
        (any::<Index>(), 1u8..16).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (any::<Index>(), any::<Index>()).prop_map(|(i, j)| Mutation::Duplicate(i, j)),
        (any::<Index>(), any::<Index>()).prop_map(|(i, t)| Mutation::InsertToken(i, t)),
        any::<Index>().prop_map(Mutation::Truncate),
    ]
}

fn apply(mut b: Vec<u8>, muts: &[Mutation], dict: &[&[u8]]) -> Vec<u8> {
    for m in muts {
        let at = |i: &Index, len: usize| if len == 0 { 0 } else { i.index(len) };
        match m {
            Mutation::FlipBit(i, bit) if !b.is_empty() => {
                let k = at(i, b.len());
                b[k] ^= 1 << bit;
            }
            Mutation::SetByte(i, v) if !b.is_empty() => {
                let k = at(i, b.len());
                b[k] = *v;
            }
            Mutation::InsertByte(i, v) => {
                let k = at(i, b.len() + 1);
                b.insert(k, *v);
            }
            Mutation::Delete(i, n) if !b.is_empty() => {
                let k = at(i, b.len());
                let end = (k + *n as usize).min(b.len());
                b.drain(k..end);
            }
            Mutation::Duplicate(i, j) if !b.is_empty() => {
                let k = at(i, b.len());
                let end = (k + 1 + at(j, 64)).min(b.len());
                let chunk = b[k..end].to_vec();
                b.splice(end..end, chunk);
            }
            Mutation::InsertToken(i, t) => {
                let k = at(i, b.len() + 1);
                let tok = dict[t.index(dict.len())];
                b.splice(k..k, tok.iter().copied());
            }
            Mutation::Truncate(i) => {
                let k = at(i, b.len() + 1);
                b.truncate(k);
            }
            _ => {}
        }
    }
    b
}

/// Binary STL with random float bit patterns, sized to match its count (or not).
fn binary_stl() -> impl Strategy<Value = Vec<u8>> {
    (
        prop::collection::vec(prop::collection::vec(any::<u32>(), 9), 0..16),
        0u8..4,
        any::<bool>(),
    )
        .prop_map(|(tris, small, solid)| {
            let mut out = vec![0u8; 80];
            if solid {
                out[..5].copy_from_slice(b"solid");
            }
            out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
            for t in &tris {
                out.extend_from_slice(&[0; 12]);
                for bits in t {
                    // Mostly small coordinates (shared corners, degenerate triangles), sometimes
                    // any bit pattern (NaN, inf, denormals).
                    let v = if small > 0 {
                        (bits % 4) as f32
                    } else {
                        f32::from_bits(*bits)
                    };
                    out.extend_from_slice(&v.to_le_bytes());
                }
                out.extend_from_slice(&[0; 2]);
            }
            out
        })
}

/// A PLY file with a vertex element (x, y, z of random types among other properties), a face
/// element (an index list of random integer types among other properties), maybe an extra element,
/// random counts, and a body of small random values: it gets past the header and into the body.
fn random_ply() -> impl Strategy<Value = Vec<u8>> {
    let all = || {
        select(vec![
            "char", "uchar", "short", "ushort", "int", "uint", "float", "double",
        ])
    };
    let int = || select(vec!["char", "uchar", "short", "ushort", "int", "uint"]);
    let extra = (any::<bool>(), all(), all()).prop_map(|(list, a, b)| {
        if list {
            format!(
                "property list {} {b} extra\n",
                if a.starts_with('f') || a == "double" {
                    "uchar"
                } else {
                    a
                }
            )
        } else {
            format!("property {a} extra\n")
        }
    });
    let count = || select(vec![0u64, 1, 2, 3, 4, 8, 255, 65536, 4_000_000_000]);
    (
        select(vec!["ascii", "binary_little_endian", "binary_big_endian"]),
        (
            count(),
            all(),
            all(),
            all(),
            prop::collection::vec(extra.clone(), 0..3),
            any::<Index>(),
        ),
        (
            count(),
            int(),
            int(),
            prop::collection::vec(extra.clone(), 0..2),
            any::<bool>(),
        ),
        prop::option::of((count(), prop::collection::vec(extra, 0..3))),
        prop::collection::vec(
            select(vec![0u8, 0, 0, 1, 2, 3, 4, 0x3f, 0x80, 0xff]),
            0..512,
        ),
        prop::collection::vec(
            select(vec![
                "0", "1", "2", "3", "4", "-1", "0.5", "nan", "300", "\n",
            ]),
            0..128,
        ),
    )
        .prop_map(
            |(
                fmt,
                (nv, tx, ty, tz, vextra, at),
                (nf, ct, it, fextra, faces_first),
                other,
                bin,
                words,
            )| {
                let mut vprops: Vec<String> = vec![
                    format!("property {tx} x\n"),
                    format!("property {ty} y\n"),
                    format!("property {tz} z\n"),
                ];
                for (k, e) in vextra.into_iter().enumerate() {
                    let i = (at.index(vprops.len() + 1) + k) % (vprops.len() + 1);
                    vprops.insert(i, e);
                }
                let vertex = format!("element vertex {nv}\n{}", vprops.concat());
                let face = format!(
                    "element face {nf}\nproperty list {ct} {it} vertex_indices\n{}",
                    fextra.concat()
                );
                let mut s = format!("ply\nformat {fmt} 1.0\n");
                if faces_first {
                    s += &face;
                    s += &vertex;
                } else {
                    s += &vertex;
                    s += &face;
                }
                if let Some((n, props)) = other {
                    s += &format!("element other {n}\n{}", props.concat());
                }
                s += "end_header\n";
                let mut out = s.into_bytes();
                if fmt == "ascii" {
                    for w in &words {
                        out.extend_from_slice(w.as_bytes());
                        out.push(b' ');
                    }
                } else {
                    out.extend_from_slice(&bin);
                }
                out
            },
        )
}

fn inputs(format: Format) -> BoxedStrategy<Vec<u8>> {
    let seeds = seeds(format);
    let dict = dictionary(format);
    let dict2 = dict.clone();
    let mutated = (select(seeds), prop_oneof![3 => prop::collection::vec(mutation(), 1..3), 1 => prop::collection::vec(mutation(), 3..10)])
        .prop_map(move |(seed, muts)| apply(seed, &muts, &dict));
    let soup = prop::collection::vec(select(dict2), 0..200).prop_map(|toks| toks.concat());
    let random = prop::collection::vec(any::<u8>(), 0..512);
    match format {
        Format::Stl => prop_oneof![4 => mutated, 2 => soup, 1 => random, 2 => binary_stl()].boxed(),
        Format::Ply => prop_oneof![4 => mutated, 2 => soup, 1 => random, 2 => random_ply()].boxed(),
        _ => prop_oneof![5 => mutated, 3 => soup, 1 => random].boxed(),
    }
}

fn fuzz(format: Format, cases: u32) {
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: 10_000,
        ..Config::default()
    });
    let start = Instant::now();
    let (ok, bytes_seen) = (Cell::new(0u64), Cell::new(0u64));
    let result = runner.run(&inputs(format), |bytes| {
        bytes_seen.set(bytes_seen.get() + bytes.len() as u64);
        if let Ok(s) = load_bytes(&bytes, format, "fuzz", None) {
            ok.set(ok.get() + 1);
            assert_corner_attributes(&s);
        }
        Ok(())
    });
    // The share of inputs that load shows the cases reach past the first checks.
    eprintln!(
        "fuzz {format:?}: {cases} cases ({} loaded, {} bytes) in {:.2} s",
        ok.get(),
        bytes_seen.get(),
        start.elapsed().as_secs_f64()
    );
    if let Err(e) = result {
        panic!("{format:?} loader panicked: {e}");
    }
}

fn long_cases() -> u32 {
    cases_from_env("SIGHTLINE_FUZZ_CASES", 1_000_000)
}

#[test]
fn fuzz_obj() {
    fuzz(Format::Obj, DEFAULT_CASES);
}

#[test]
fn fuzz_stl() {
    fuzz(Format::Stl, DEFAULT_CASES);
}

#[test]
fn fuzz_ply() {
    fuzz(Format::Ply, DEFAULT_CASES);
}

#[test]
#[ignore = "long: SIGHTLINE_FUZZ_CASES cases (default 1,000,000)"]
fn fuzz_obj_long() {
    fuzz(Format::Obj, long_cases());
}

#[test]
#[ignore = "long: SIGHTLINE_FUZZ_CASES cases (default 1,000,000)"]
fn fuzz_stl_long() {
    fuzz(Format::Stl, long_cases());
}

#[test]
#[ignore = "long: SIGHTLINE_FUZZ_CASES cases (default 1,000,000)"]
fn fuzz_ply_long() {
    fuzz(Format::Ply, long_cases());
}

/// MTL files are only read through an OBJ's `mtllib` from a directory, so this one goes through
/// the file system: each case rewrites `m.mtl` next to a one-triangle OBJ that uses it.
fn fuzz_mtl(cases: u32) {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("t.obj");
    let mtl = dir.path().join("m.mtl");
    std::fs::write(
        &obj,
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
    )
    .unwrap();
    let seed = std::fs::read(fixtures_dir().join("cube.mtl")).unwrap();
    let dict: Vec<&'static [u8]> = vec![
        b"newmtl",
        b"red",
        b"Kd",
        b"Ke",
        b"Ka",
        b"d",
        b"-halo",
        b"Tr",
        b"spectral",
        b"map_Kd",
        b" ",
        b"\n",
        b"\r\n",
        b"#",
        b"0",
        b"1",
        b"0.5",
        b"-1",
        b"2",
        b"nan",
        b"inf",
        b"1e999",
        b"\xff",
    ];
    let dict2 = dict.clone();
    let strategy = prop_oneof![
        prop::collection::vec(mutation(), 1..6).prop_map(move |m| apply(seed.clone(), &m, &dict)),
        prop::collection::vec(select(dict2), 0..60).prop_map(|t| t.concat()),
    ];
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let start = Instant::now();
    let result = runner.run(&strategy, |bytes| {
        std::fs::write(&mtl, &bytes).unwrap();
        let _ = sightline::scene::load(&obj, None);
        Ok(())
    });
    eprintln!(
        "fuzz mtl: {cases} cases in {:.2} s",
        start.elapsed().as_secs_f64()
    );
    if let Err(e) = result {
        panic!("MTL loading panicked: {e}");
    }
}

#[test]
fn fuzz_mtl_files() {
    fuzz_mtl(5_000);
}

#[test]
#[ignore = "long: SIGHTLINE_FUZZ_CASES / 10 cases (it writes a file per case)"]
fn fuzz_mtl_long() {
    fuzz_mtl(long_cases() / 10);
}

#[test]
fn grid_seeds_load() {
    for f in [Format::Obj, Format::Stl, Format::Ply] {
        for b in grid_seeds(f) {
            match load_bytes(&b, f, "grid", None) {
                Err(e) => panic!("{e}"),
                // The OBJ grid's attributes reach the scene.
                Ok(s) if f == Format::Obj => {
                    assert!(s.corner_uvs.iter().any(Option::is_some));
                    assert!(s.corner_normals.iter().any(Option::is_some));
                    assert!(s.corner_uvs.iter().any(Option::is_none));
                }
                Ok(_) => {}
            }
        }
    }
}
