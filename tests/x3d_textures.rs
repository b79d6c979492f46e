//! X3D texture coordinates, normals and ImageTexture: the indexing rules, the errors, and the
//! textured quad rendered like its OBJ twin (tests/shading.rs).

mod support;

use glam::{DMat4, DVec3};
use sightline::raster::lighting::Textures;
use sightline::scene::{Format, load_bytes};
use sightline::{Location, Scene};
use support::fixtures::{fixture, fixtures_dir};
use support::render::flat_headlight;

/// Loads X3D text as if it were a file in `fixtures/`.
fn x3d(text: &str) -> Scene {
    try_x3d(text).unwrap_or_else(|e| panic!("{e}"))
}

fn try_x3d(text: &str) -> Result<Scene, sightline::LoadError> {
    load_bytes(text.as_bytes(), Format::X3d, "t.x3d", Some(&fixtures_dir()))
}

/// A Shape around `geometry` with a checker16 texture.
fn textured(geometry: &str) -> String {
    format!(
        r#"<X3D><Scene><Shape><Appearance><Material diffuseColor="0.5 0 0"/>
        <ImageTexture url='"checker16.png"'/></Appearance>{geometry}</Shape></Scene></X3D>"#
    )
}

fn uvs_of(s: &Scene, f: usize) -> Vec<[f64; 2]> {
    s.face_corner_uvs(&s.faces[f]).unwrap()
}

fn normals_of(s: &Scene, f: usize) -> Vec<DVec3> {
    s.face_corner_normals(&s.faces[f]).unwrap()
}

#[test]
fn checker_fixture_has_uvs_normals_and_texture() {
    let s = fixture("checker_quad.x3d");
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    assert_eq!(s.faces.len(), 1);
    assert_eq!(
        uvs_of(&s, 0),
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    assert_eq!(normals_of(&s, 0), [DVec3::Z; 4]);
    // The second url, the first that exists.
    let m = s.faces[0].material;
    assert_eq!(
        s.texture_of(m),
        Some(fixtures_dir().join("checker16.png").as_path())
    );
    // X3D: the texture replaces the diffuse colour.
    assert_eq!(s.materials[m as usize].diffuse, [1.0; 3]);
}

/// The same camera and lighting as tests/shading.rs's OBJ checker quad.
fn render(scene: &Scene, size: u32) -> Vec<[f64; 3]> {
    flat_headlight(scene, size)
}

#[test]
fn x3d_checker_renders_like_the_obj_checker() {
    let x = fixture("checker_quad.x3d");
    let o = fixture("checker_quad.obj");
    for size in [16, 8] {
        let (a, b) = (render(&x, size), render(&o, size));
        assert_eq!(a, b, "size {size}");
    }
    // And it is the checkerboard (white at the top left), not a uniform colour.
    let img = render(&x, 16);
    for (k, px) in img.iter().enumerate() {
        let want = if (k % 16 + k / 16) % 2 == 0 { 1.0 } else { 0.0 };
        assert!(
            px.iter().all(|c| (c - want).abs() < 1e-9),
            "pixel {k}: {px:?}"
        );
    }
}

#[test]
fn without_tex_coord_index_the_coord_index_is_used() {
    let s = x3d(&textured(
        r#"<IndexedFaceSet coordIndex="0 1 2 -1 2 3 0">
             <Coordinate point="0 0 0 1 0 0 1 1 0 0 1 0"/>
             <TextureCoordinate point="0 0 0.25 0 0.5 0.5 0 0.75"/>
             <Normal vector="0 0 1 0 0 2 0 0 3 0 0 4"/>
           </IndexedFaceSet>"#,
    ));
    assert_eq!(uvs_of(&s, 0), [[0.0, 0.0], [0.25, 0.0], [0.5, 0.5]]);
    assert_eq!(uvs_of(&s, 1), [[0.5, 0.5], [0.0, 0.75], [0.0, 0.0]]);
    let z = |f| normals_of(&s, f).iter().map(|n| n.z).collect::<Vec<_>>();
    assert_eq!((z(0), z(1)), (vec![1.0, 2.0, 3.0], vec![3.0, 4.0, 1.0]));
    assert!(s.texture_of(s.faces[0].material).is_some());
}

#[test]
fn own_indices_normal_per_face_and_ccw_false() {
    let s = x3d(&textured(
        r#"<IndexedFaceSet ccw="false" normalPerVertex="false" normalIndex="1 0"
             coordIndex="0 3 2 1 -1 0 1 3" texCoordIndex="1 1 0 0 -1 0 1 1">
             <Coordinate point="0 0 0 1 0 0 1 1 0 0 1 0"/>
             <TextureCoordinate point="0.5 0.5 1 1"/>
             <Normal vector="0 0 1 0 0 -1"/>
           </IndexedFaceSet>"#,
    ));
    // ccw="false": corners reversed, each keeping its own uv.
    assert_eq!(s.face_corners(&s.faces[0]), [1, 2, 3, 0]);
    assert_eq!(
        uvs_of(&s, 0),
        [[0.5, 0.5], [0.5, 0.5], [1.0, 1.0], [1.0, 1.0]]
    );
    assert_eq!(uvs_of(&s, 1), [[1.0, 1.0], [1.0, 1.0], [0.5, 0.5]]);
    // One normal per face, by normalIndex.
    assert_eq!(normals_of(&s, 0), [DVec3::NEG_Z; 4]);
    assert_eq!(normals_of(&s, 1), [DVec3::Z; 3]);
}

#[test]
fn triangle_sets_take_attributes_in_order_and_normals_are_transformed() {
    let s = x3d(
        r#"<Scene><Transform scale="2 1 1" rotation="0 0 1 1.5707963267948966">
        <Shape><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/>
          <Normal vector="1 0 1 1 0 1 1 0 1"/></TriangleSet></Shape>
        <Shape><IndexedTriangleSet index="0 1 2 2 1 3" normalPerVertex="false">
          <Coordinate point="0 0 0 1 0 0 0 1 0 1 1 1"/>
          <TextureCoordinate point="0 0 1 0 0 1 1 1"/>
          <Normal vector="0 0 1 0 0 -1"/></IndexedTriangleSet></Shape>
      </Transform></Scene>"#,
    );
    // Normal (1, 0, 1) under R·S (S = diag(2,1,1), R = 90° about z): the inverse transpose
    // gives R·(0.5, 0, 1) = (0, 0.5, 1) up to a positive factor.
    let m = DMat4::from_rotation_z(std::f64::consts::FRAC_PI_2)
        * DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0));
    assert!(m.determinant() > 0.0);
    for n in normals_of(&s, 0) {
        let n = n.normalize();
        let want = DVec3::new(0.0, 0.5, 1.0).normalize();
        assert!((n - want).length() < 1e-12, "{n}");
    }
    assert!(s.face_corner_uvs(&s.faces[0]).is_none());
    assert_eq!(uvs_of(&s, 1), [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    assert_eq!(uvs_of(&s, 2), [[0.0, 1.0], [1.0, 0.0], [1.0, 1.0]]);
    assert_eq!(normals_of(&s, 1), [DVec3::Z * 2.0; 3]);
    assert_eq!(normals_of(&s, 2), [DVec3::NEG_Z * 2.0; 3]);
    assert_eq!(s.corner_uvs.len(), s.corners.len());
}

#[test]
fn texture_rules() {
    // A missing image is not a load error: the path is kept (the renderer warns), the diffuse
    // colour stays.
    let s = x3d(&textured(
        r#"<TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/>
           <TextureCoordinate point="0 0 1 0 0 1"/></TriangleSet>"#,
    )
    .replace("checker16.png", "nowhere.png"));
    let m = s.faces[0].material;
    assert_eq!(
        s.texture_of(m),
        Some(fixtures_dir().join("nowhere.png").as_path())
    );
    assert_eq!(s.materials[m as usize].diffuse, [0.5, 0.0, 0.0]);
    let t = Textures::load(&s);
    assert_eq!(t.warnings.len(), 1, "{:?}", t.warnings);
    // An unquoted url is one file name; a texture on geometry without TextureCoordinate is not
    // applied, with a warning, and keeps the diffuse colour.
    let s = x3d(
        r#"<Scene><Shape><Appearance><Material diffuseColor="0.5 0 0"/>
        <ImageTexture url="checker16.png"/></Appearance><Box/></Shape></Scene>"#,
    );
    assert_eq!(s.texture_of(s.faces[0].material), None);
    assert_eq!(s.materials[0].diffuse, [0.5, 0.0, 0.0]);
    assert!(
        s.stats
            .warnings
            .iter()
            .any(|w| w.contains("<ImageTexture> not applied")),
        "{:?}",
        s.stats.warnings
    );
    let tri = r#"<TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/>
        <TextureCoordinate point="0 0 1 0 0 1"/></TriangleSet>"#;
    // Urls with a scheme are not read; with no directory none is.
    let s = x3d(&textured(tri).replace("\"checker16.png\"", "\"http://x/checker16.png\""));
    assert_eq!(s.texture_of(0), None);
    let s = load_bytes(textured(tri).as_bytes(), Format::X3d, "t.x3d", None).unwrap();
    assert_eq!(s.texture_of(0), None);
    assert!(s.stats.warnings.iter().any(|w| w.contains("no directory")));
    // Unquoted in the XML, unquoted unknown: the first of several quoted strings that exists.
    let s = x3d(&textured(tri).replace("\"checker16.png\"", r#""a b.png", "checker16.png""#));
    assert_eq!(
        s.texture_of(0),
        Some(fixtures_dir().join("checker16.png").as_path())
    );
    assert_eq!(s.materials[0].diffuse, [1.0; 3]);
}

/// Each case: geometry, element, words the message must contain.
#[test]
fn attribute_errors_name_element_and_attribute() {
    let cases: &[(&str, &str, &[&str])] = &[
        (
            r#"<IndexedFaceSet coordIndex="0 1 2"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1"/></IndexedFaceSet>"#,
            "TextureCoordinate",
            &["attribute 'point'", "3 numbers", "multiple of 2"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1 0"/></IndexedFaceSet>"#,
            "Normal",
            &["attribute 'vector'", "4 numbers", "multiple of 3"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 x"/></IndexedFaceSet>"#,
            "Normal",
            &["attribute 'vector'", "'x'", "not a number"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1 0"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &[
                "attribute 'coordIndex'",
                "index 2",
                "out of range",
                "TextureCoordinate has 2 point",
            ],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2" texCoordIndex="0 1 5">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1 0 1 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &[
                "attribute 'texCoordIndex'",
                "index 5",
                "TextureCoordinate has 3 point",
            ],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2 -1" texCoordIndex="0 1 2">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1 0 1 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &[
                "attribute 'texCoordIndex'",
                "3 value(s)",
                "fewer than the 4",
            ],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2 -1" normalIndex="0 0 -1 0">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &["attribute 'normalIndex'", "value 3", "same places"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2" normalIndex="0 0 -2">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &["attribute 'normalIndex'", "-2", "below -1"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2" normalIndex="0 1 0">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &["attribute 'normalIndex'", "index 1", "Normal has 1 vector"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2 -1 0 2 1" normalPerVertex="false">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &["<Normal> has 1 value(s), 2 are needed", "one per face"],
        ),
        (
            r#"<TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1 0"/></TriangleSet>"#,
            "TriangleSet",
            &[
                "<TextureCoordinate> has 2 value(s), 3 are needed",
                "one per vertex",
            ],
        ),
        (
            r#"<IndexedTriangleSet index="0 1 2"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <Normal vector="0 0 1"/></IndexedTriangleSet>"#,
            "IndexedTriangleSet",
            &["attribute 'index'", "Normal has 1 vector"],
        ),
        (
            r#"<IndexedFaceSet coordIndex="0 1 2" texCoordIndex="0 x 1">
               <Coordinate point="0 0 0 1 0 0 0 1 0"/>
               <TextureCoordinate point="0 0 1 0"/></IndexedFaceSet>"#,
            "IndexedFaceSet",
            &["attribute 'texCoordIndex'", "'x'", "not an integer"],
        ),
    ];
    for (geometry, element, words) in cases {
        let text = format!("<Scene>\n<Shape>{geometry}</Shape></Scene>");
        let e = match try_x3d(&text) {
            Ok(_) => panic!("{geometry}: loaded"),
            Err(e) => e,
        };
        assert_eq!(e.file, "t.x3d");
        match &e.location {
            Location::Element { name, line } => {
                assert_eq!(name, element, "{e}");
                assert!(*line >= 2, "{e}");
            }
            other => panic!("{other:?}"),
        }
        for w in *words {
            assert!(e.message.contains(w), "{e} lacks {w:?}");
        }
    }
    // A malformed url.
    for (url, words) in [
        (r#""a.png"#, &["attribute 'url'", "no closing"][..]),
        (
            r#""a.png" b.png"#,
            &["attribute 'url'", "string 2", "start with"][..],
        ),
    ] {
        let text = textured("<Box/>").replace(r#"'"checker16.png"'"#, &format!("'{url}'"));
        let e = try_x3d(&text).unwrap_err();
        assert!(
            matches!(&e.location, Location::Element { name, .. } if name == "ImageTexture"),
            "{e}"
        );
        for w in words {
            assert!(e.message.contains(w), "{e} lacks {w:?}");
        }
    }
}
