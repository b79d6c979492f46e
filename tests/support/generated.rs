//! The generated fixtures: the unit cube they share, and writers for the STL and PLY fixtures
//! (binary ones cannot be written by hand; the text ones are generated too so that every format
//! holds exactly the same cube). `tests/fixture_gen.rs` keeps `fixtures/` equal to them.

/// The unit cube [0,1]^3.
pub const CUBE_VERTICES: [[f64; 3]; 8] = [
    [0., 0., 0.],
    [1., 0., 0.],
    [1., 1., 0.],
    [0., 1., 0.],
    [0., 0., 1.],
    [1., 0., 1.],
    [1., 1., 1.],
    [0., 1., 1.],
];

/// Its faces, counter-clockwise seen from outside: bottom, top, front, back, left, right (the
/// order `fixtures/cube.obj` uses too).
pub const CUBE_QUADS: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [0, 4, 7, 3],
    [1, 2, 6, 5],
];

/// The cube's triangles: each quad (a, b, c, d) as (a, b, c), (a, c, d).
pub fn cube_triangles() -> Vec<[[f64; 3]; 3]> {
    let mut out = Vec::new();
    for q in CUBE_QUADS {
        let p = q.map(|i| CUBE_VERTICES[i]);
        out.push([p[0], p[1], p[2]]);
        out.push([p[0], p[2], p[3]]);
    }
    out
}

fn normal(t: &[[f64; 3]; 3]) -> [f64; 3] {
    let u = [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]];
    let v = [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]];
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

pub fn cube_ascii_stl() -> Vec<u8> {
    let mut s = String::from("solid cube\n");
    for t in cube_triangles() {
        let n = normal(&t);
        s += &format!(
            "  facet normal {:.6e} {:.6e} {:.6e}\n    outer loop\n",
            n[0], n[1], n[2]
        );
        for v in t {
            s += &format!("      vertex {:.6e} {:.6e} {:.6e}\n", v[0], v[1], v[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid cube\n";
    s.into_bytes()
}

/// A binary STL of `tris`; `header` goes at the start of the 80-byte header.
pub fn binary_stl(header: &str, tris: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![b' '; 80];
    out[..header.len()].copy_from_slice(header.as_bytes());
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        for c in normal(t) {
            out.extend_from_slice(&(c as f32).to_le_bytes());
        }
        for v in t {
            for c in v {
                out.extend_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// The binary cube STL; its header starts with "solid" on purpose (as many exporters' do).
pub fn cube_binary_stl() -> Vec<u8> {
    binary_stl(
        "solid cube: a binary STL whose header starts with 'solid'",
        &cube_triangles(),
    )
}

/// ASCII PLY cube with vertex colours and an extra `edge` element to skip.
pub fn cube_ascii_ply() -> Vec<u8> {
    let mut s = String::from(
        "ply\nformat ascii 1.0\ncomment unit cube, quads counter-clockwise seen from outside\n\
         element vertex 8\nproperty float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face 6\nproperty list uchar int vertex_indices\nproperty uchar flags\n\
         element edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n",
    );
    for v in CUBE_VERTICES {
        s += &format!("{} {} {} 255 0 0\n", v[0], v[1], v[2]);
    }
    for q in CUBE_QUADS {
        s += &format!("4 {} {} {} {} 1\n", q[0], q[1], q[2], q[3]);
    }
    s += "0 1\n1 2\n";
    s.into_bytes()
}

/// Binary PLY cube. Little-endian: double coordinates with an interleaved `short` property, faces
/// `list uchar uint vertex_indices` followed by a skipped list. Big-endian: float coordinates,
/// faces `list uint8 int32 vertex_index`, and an extra element after the faces.
pub fn cube_binary_ply(big_endian: bool) -> Vec<u8> {
    let mut out: Vec<u8> = Vec::new();
    let put = |out: &mut Vec<u8>, le: &[u8]| {
        if big_endian {
            out.extend(le.iter().rev());
        } else {
            out.extend_from_slice(le);
        }
    };
    if big_endian {
        out.extend_from_slice(
            b"ply\nformat binary_big_endian 1.0\ncomment unit cube\nelement vertex 8\n\
              property float32 x\nproperty float32 y\nproperty float32 z\n\
              element face 6\nproperty list uint8 int32 vertex_index\n\
              element material 1\nproperty uchar red\nproperty list ushort float weights\nend_header\n",
        );
        for v in CUBE_VERTICES {
            for c in v {
                put(&mut out, &(c as f32).to_le_bytes());
            }
        }
        for q in CUBE_QUADS {
            out.push(4);
            for i in q {
                put(&mut out, &(i as i32).to_le_bytes());
            }
        }
        out.push(200);
        put(&mut out, &2u16.to_le_bytes());
        put(&mut out, &0.5f32.to_le_bytes());
        put(&mut out, &0.25f32.to_le_bytes());
    } else {
        out.extend_from_slice(
            b"ply\r\nformat binary_little_endian 1.0\r\ncomment unit cube\r\nelement vertex 8\r\n\
              property double x\r\nproperty short tag\r\nproperty double y\r\nproperty double z\r\n\
              element face 6\r\nproperty list uchar uint vertex_indices\r\n\
              property list uchar float texcoord\r\nend_header\r\n",
        );
        for (k, v) in CUBE_VERTICES.iter().enumerate() {
            put(&mut out, &v[0].to_le_bytes());
            put(&mut out, &(k as i16 - 4).to_le_bytes());
            put(&mut out, &v[1].to_le_bytes());
            put(&mut out, &v[2].to_le_bytes());
        }
        for q in CUBE_QUADS {
            out.push(4);
            for i in q {
                put(&mut out, &(i as u32).to_le_bytes());
            }
            out.push(2);
            put(&mut out, &0.5f32.to_le_bytes());
            put(&mut out, &1.0f32.to_le_bytes());
        }
    }
    out
}

/// Every generated fixture: (path under `fixtures/`, bytes).
pub fn generated_fixtures() -> Vec<(&'static str, Vec<u8>)> {
    let le = cube_binary_ply(false);
    let mut nan_tris = cube_triangles();
    nan_tris[2][1][0] = f64::NAN;
    let mut truncated_stl = cube_binary_stl();
    truncated_stl.truncate(84 + 50 * 5 + 30);
    let mut huge = b"ply\nformat binary_little_endian 1.0\ncomment the count below is a lie: only 8 vertices follow\n\
        element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n\
        element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
    for v in CUBE_VERTICES {
        for c in v {
            huge.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    huge.extend_from_slice(&[3, 0, 0, 0]);
    vec![
        ("cube_ascii.stl", cube_ascii_stl()),
        ("cube_binary.stl", cube_binary_stl()),
        ("cube_ascii.ply", cube_ascii_ply()),
        ("cube_binary_le.ply", le.clone()),
        ("cube_binary_be.ply", cube_binary_ply(true)),
        ("bad/stl_truncated.stl", truncated_stl),
        (
            "bad/stl_nan.stl",
            binary_stl("binary cube with a NaN in triangle 3", &nan_tris),
        ),
        ("bad/ply_truncated_binary.ply", le[..le.len() - 3].to_vec()),
        ("bad/ply_huge_count.ply", huge),
    ]
}
