//! X3D loading and generated primitives: world-space coordinates, transform composition,
//! materials, viewpoints, warnings, and closed, outward primitive meshes.

mod support;

use glam::{DMat4, DQuat, DVec3};
use sightline::scene::primitives::{self, Parts};
use sightline::scene::{Format, SceneBuilder, load_bytes};
use sightline::{Location, Material, Scene};
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};
use support::fixtures::fixture;

fn x3d(text: &str) -> Scene {
    load_bytes(text.as_bytes(), Format::X3d, "inline.x3d", None).unwrap_or_else(|e| panic!("{e}"))
}

/// Checks the corners of face `i` against `want`, each coordinate to within `tol`.
fn assert_face(s: &Scene, i: usize, want: &[[f64; 3]], tol: f64) {
    let got: Vec<DVec3> = s.face_positions(&s.faces[i]).collect();
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (*g - DVec3::from_array(*w)).abs().max_element() <= tol,
            "{got:?} vs {want:?}"
        );
    }
}

/// Checks that the faces of a mesh use every directed edge once and its reverse once (by vertex
/// index), and returns the signed volume (positive when the faces point outward).
fn closed_volume(s: &Scene, faces: std::ops::Range<usize>) -> f64 {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    let mut volume = 0.0;
    for f in &s.faces[faces] {
        let c = s.face_corners(f);
        for k in 0..c.len() {
            *edges.entry((c[k], c[(k + 1) % c.len()])).or_default() += 1;
        }
        let p: Vec<DVec3> = s.face_positions(f).collect();
        for k in 1..p.len() - 1 {
            volume += p[0].dot(p[k].cross(p[k + 1])) / 6.0;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a}->{b} used {n} times in one direction");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "edge {a}->{b} has no opposite twin"
        );
    }
    volume
}

fn mesh_volume(s: &Scene, name: &str) -> f64 {
    let m = s
        .meshes
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no mesh {name}"));
    closed_volume(s, m.faces.clone())
}

fn material_of(s: &Scene, face: usize) -> &Material {
    &s.materials[s.faces[face].material as usize]
}

#[test]
fn seed_two_triangles_in_world_space() {
    let s = fixture("seed_two_triangles.x3d");
    assert_eq!(s.faces.len(), 2);
    assert_eq!(s.meshes.len(), 2);
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    // Red at z = 0 moved +1 in x; blue at z = -1 moved -1 in x.
    assert_face(&s, 0, &[[-1., -2., 0.], [3., -2., 0.], [1., 2., 0.]], 0.0);
    assert_face(
        &s,
        1,
        &[[-3., -2., -1.], [1., -2., -1.], [-1., 2., -1.]],
        0.0,
    );
    let (red, blue) = (material_of(&s, 0), material_of(&s, 1));
    assert_eq!(red.emissive, [1.0, 0.0, 0.0]);
    assert_eq!(
        red.diffuse, [0.0; 3],
        "emissive-only material is drawn unlit"
    );
    assert_eq!(blue.emissive, [0.0, 0.0, 1.0]);
    assert_eq!(blue.diffuse, [0.0; 3]);
    assert_eq!(red.transparency, 0.0);
    assert!(!red.two_sided && !blue.two_sided);
    // Counter-clockwise seen from the camera at +z.
    assert!(s.face_normal(&s.faces[0]).z > 0.0);
    let vp = s.viewpoint.expect("viewpoint");
    assert_eq!(vp.position, DVec3::new(0.0, 0.0, 8.0));
    assert_eq!(vp.orientation_angle, 0.0);
    assert_eq!(vp.field_of_view, PI / 4.0);
}

#[test]
fn seed_transparent_variant() {
    let s = fixture("seed_transparent.x3d");
    assert_eq!(s.faces.len(), 2);
    // Blue, opaque, drawn first: z = -1 moved +1 in x.
    assert_face(
        &s,
        0,
        &[[-1., -2., -1.], [3., -2., -1.], [1., 2., -1.]],
        0.0,
    );
    assert_eq!(material_of(&s, 0).emissive, [0.0, 0.0, 1.0]);
    assert_eq!(material_of(&s, 0).transparency, 0.0);
    // Green, transparent, last: z = 0 moved -1 in x.
    assert_face(&s, 1, &[[-3., -2., 0.], [1., -2., 0.], [-1., 2., 0.]], 0.0);
    assert_eq!(material_of(&s, 1).emissive, [0.0, 1.0, 0.0]);
    assert_eq!(material_of(&s, 1).diffuse, [0.0; 3]);
    assert_eq!(material_of(&s, 1).transparency, 0.4);
    assert_eq!(s.viewpoint.unwrap().position, DVec3::new(0.0, 0.0, 8.0));
}

#[test]
fn nested_transforms_compose_in_x3d_order() {
    // Inner: P' = T·C·R·S·-C·P with C = (1,0,0), R = 90° about z, S = (2,3,1), T = (0,0,5).
    // Outer: scale (1,1,2) then translate (10,0,0).
    // (2,1,0) -> -C (1,1,0) -> S (2,3,0) -> R (-3,2,0) -> C (-2,2,0) -> T (-2,2,5)
    //         -> outer S (-2,2,10) -> outer T (8,2,10).
    // (1,0,0) is the centre: -> (1,0,5) -> (1,0,10) -> (11,0,10).
    // (1,0,1) -> -C (0,0,1) -> S (0,0,1) -> R (0,0,1) -> C (1,0,1) -> T (1,0,6) -> (11,0,12).
    let s = x3d(r#"<X3D><Scene>
        <Transform translation="10 0 0" scale="1 1 2">
         <Transform translation="0 0 5" center="1 0 0" rotation="0 0 1 1.5707963267948966"
                    scale="2 3 1">
          <Shape><TriangleSet><Coordinate point="2 1 0  1 0 0  1 0 1"/></TriangleSet></Shape>
         </Transform>
        </Transform>
        </Scene></X3D>"#);
    assert_face(
        &s,
        0,
        &[[8., 2., 10.], [11., 0., 10.], [11., 0., 12.]],
        1e-12,
    );
}

#[test]
fn scale_orientation_scales_along_the_rotated_axes() {
    // Scaling x by 2 in a frame turned 90° about z scales y by 2.
    let s = x3d(r#"<Scene>
        <Transform scale="2 1 1" scaleOrientation="0 0 1 1.5707963267948966" translation="0 0 1">
          <Shape><TriangleSet><Coordinate point="1 1 0  0 0 0  1 0 0"/></TriangleSet></Shape>
        </Transform></Scene>"#);
    assert_face(&s, 0, &[[1., 2., 1.], [0., 0., 1.], [1., 0., 1.]], 1e-12);
}

#[test]
fn transform_matches_the_matrix_formula() {
    let (t, c, s) = (
        DVec3::new(0.5, -2.0, 3.0),
        DVec3::new(1.0, 2.0, -1.0),
        DVec3::new(2.0, 0.5, 3.0),
    );
    let r = DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.7);
    let sr = DQuat::from_axis_angle(DVec3::new(0.0, 1.0, 1.0).normalize(), -0.4);
    let m = DMat4::from_translation(t)
        * DMat4::from_translation(c)
        * DMat4::from_quat(r)
        * DMat4::from_quat(sr)
        * DMat4::from_scale(s)
        * DMat4::from_quat(sr.inverse())
        * DMat4::from_translation(-c);
    let points = [[0.3, 0.2, 0.1], [1.0, -1.0, 2.0], [-2.0, 0.5, 0.0]];
    let text = format!(
        r#"<Scene><Transform translation="0.5 -2 3" center="1 2 -1" rotation="1 1 0 0.7"
              scale="2 0.5 3" scaleOrientation="0 1 1 -0.4">
          <Shape><TriangleSet><Coordinate point="{}"/></TriangleSet></Shape>
        </Transform></Scene>"#,
        points
            .iter()
            .flatten()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    );
    let scene = x3d(&text);
    let want: Vec<[f64; 3]> = points
        .iter()
        .map(|p| m.transform_point3(DVec3::from_array(*p)).to_array())
        .collect();
    assert_face(&scene, 0, &want, 1e-12);
}

#[test]
fn primitives_fixture_meshes_are_closed_with_analytic_volumes() {
    let s = fixture("primitives.x3d");
    assert_eq!(s.meshes.len(), 4);
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    // Box 2×2×2 scaled (1, 0.5, 2): rotations and translations keep volume.
    let v = mesh_volume(&s, "box");
    assert!((v - 8.0).abs() < 1e-9, "box {v}");
    let v = mesh_volume(&s, "sphere");
    let want = 4.0 / 3.0 * PI * 0.75f64.powi(3);
    assert!(
        v > 0.0 && (v / want - 1.0).abs() < 0.02,
        "sphere {v} vs {want}"
    );
    let v = mesh_volume(&s, "cone");
    let want = PI * 0.8 * 0.8 * 1.5 / 3.0;
    assert!(
        v > 0.0 && (v / want - 1.0).abs() < 0.02,
        "cone {v} vs {want}"
    );
    let v = mesh_volume(&s, "cylinder");
    let want = PI * 0.25 * 2.0;
    assert!(
        v > 0.0 && (v / want - 1.0).abs() < 0.02,
        "cylinder {v} vs {want}"
    );
    // The Viewpoint inside Transform(translation 0 1 0) · Transform(rotation x -0.3).
    let vp = s.viewpoint.unwrap();
    let want = DVec3::new(0.0, 1.0 + 12.0 * 0.3f64.sin(), 12.0 * 0.3f64.cos());
    assert!((vp.position - want).length() < 1e-12, "{:?}", vp.position);
    let q = DQuat::from_axis_angle(vp.orientation_axis, vp.orientation_angle);
    let dir = q * DVec3::NEG_Z;
    let want_dir = DQuat::from_rotation_x(-0.3) * DVec3::NEG_Z;
    assert!((dir - want_dir).length() < 1e-12, "{dir} vs {want_dir}");
    assert_eq!(vp.field_of_view, 0.7);
}

#[test]
fn primitives_are_closed_outward_and_exact_where_they_can_be() {
    let mut b = SceneBuilder::new("primitives");
    let m = b.default_material();
    let spin = DMat4::from_rotation_translation(
        DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.9),
        DVec3::new(5.0, -1.0, 2.0),
    );
    let mirror = DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0));
    b.begin_mesh("box");
    primitives::add_box(&mut b, &DMat4::IDENTITY, DVec3::new(1.0, 2.0, 3.0), m);
    b.begin_mesh("mirrored box");
    primitives::add_box(&mut b, &mirror, DVec3::new(1.0, 2.0, 3.0), m);
    b.begin_mesh("sphere");
    primitives::add_sphere(&mut b, &spin, 2.0, 32, 16, m);
    b.begin_mesh("cone");
    primitives::add_cone(&mut b, &spin, 1.0, 3.0, 48, Parts::ALL, m);
    b.begin_mesh("cylinder");
    primitives::add_cylinder(&mut b, &mirror, 1.5, 2.0, 48, Parts::ALL, m);
    b.begin_mesh("torus");
    primitives::torus(&mut b, &spin, 3.0, 1.0, 48, 24, m);
    let s = b.finish().unwrap();
    assert_eq!(s.stats.degenerate_dropped, 0);

    assert_eq!(mesh_volume(&s, "box"), 6.0, "box volume is exact");
    assert_eq!(
        mesh_volume(&s, "mirrored box"),
        6.0,
        "a mirror keeps faces outward"
    );
    let checks = [
        ("sphere", 4.0 / 3.0 * PI * 8.0, 0.02),
        ("cone", PI * 3.0 / 3.0, 0.01),
        ("cylinder", PI * 2.25 * 2.0, 0.01),
        ("torus", 2.0 * PI * PI * 3.0 * 1.0, 0.02),
    ];
    for (name, want, tol) in checks {
        let v = mesh_volume(&s, name);
        assert!(
            v > 0.0 && (v / want - 1.0).abs() < tol,
            "{name}: {v} vs {want}"
        );
    }
    // Quads where the surface has quads: the untransformed box keeps its 6 quads whole.
    let boxed = &s.meshes[0];
    assert_eq!(boxed.faces.len(), 6);
    assert!(s.faces[boxed.faces.clone()].iter().all(|f| f.len == 4));
}

#[test]
fn default_x3d_primitives_are_closed() {
    let s = x3d(r#"<Scene>
        <Shape DEF="b"><Box/></Shape>
        <Shape DEF="s"><Sphere/></Shape>
        <Shape DEF="c"><Cone/></Shape>
        <Shape DEF="y"><Cylinder/></Shape>
        <Shape DEF="open"><Cylinder top="false" solid="false"/></Shape>
        </Scene>"#);
    assert_eq!(mesh_volume(&s, "b"), 8.0);
    let sphere = mesh_volume(&s, "s");
    assert!((sphere / (4.0 / 3.0 * PI) - 1.0).abs() < 0.02, "{sphere}");
    let cone = mesh_volume(&s, "c");
    assert!((cone / (2.0 * PI / 3.0) - 1.0).abs() < 0.02, "{cone}");
    let cylinder = mesh_volume(&s, "y");
    assert!((cylinder / (2.0 * PI) - 1.0).abs() < 0.02, "{cylinder}");
    // A Sphere at the default resolution: 32 segments, 16 rings.
    let m = s.meshes.iter().find(|m| m.name == "s").unwrap();
    let ids: std::collections::HashSet<u32> =
        s.faces[m.faces.clone()].iter().map(|f| f.id).collect();
    assert_eq!(ids.len(), 32 * 16);
    let open = s.meshes.iter().find(|m| m.name == "open").unwrap();
    assert_eq!(open.faces.len(), 33);
    assert!(s.materials[s.faces[open.faces.start].material as usize].two_sided);
}

#[test]
fn sphere_scene_has_about_the_requested_triangles_and_is_closed() {
    let s = primitives::sphere_scene(10_000);
    let n = s.faces.len();
    assert!((n as f64 / 10_000.0 - 1.0).abs() < 0.05, "{n} triangles");
    assert!(s.faces.iter().all(|f| f.len == 3));
    assert_eq!(s.meshes.len(), 1);
    let v = closed_volume(&s, 0..n);
    assert!((v / (4.0 / 3.0 * PI) - 1.0).abs() < 0.01, "{v}");
    let (lo, hi) = s.bounds().unwrap();
    assert_eq!((lo.y, hi.y), (-1.0, 1.0));
    assert!(s.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
    let (seg, rings) = primitives::sphere_scene_resolution(10_000);
    assert_eq!(n, 2 * seg * (rings - 1));
}

#[test]
fn random_triangle_soup_is_deterministic_and_in_the_unit_cube() {
    let a = primitives::random_triangle_soup(1000, 42);
    let b = primitives::random_triangle_soup(1000, 42);
    let c = primitives::random_triangle_soup(1000, 43);
    assert_eq!(a.positions, b.positions);
    assert_ne!(a.positions, c.positions);
    assert_eq!(a.faces.len(), 1000);
    let (lo, hi) = a.bounds().unwrap();
    assert!(lo.min_element() >= 0.0 && hi.max_element() < 1.0);
    assert!(a.materials[0].two_sided);
}

#[test]
fn indexed_fixture_reads_polygons_def_use_and_skips_unknown_nodes() {
    let s = fixture("indexed.x3d");
    assert_eq!(s.meshes.len(), 4);
    // Floor: a quad and a pentagon, two-sided.
    let floor = &s.meshes[0];
    assert_eq!(floor.name, "floor");
    let lens: Vec<u32> = s.faces[floor.faces.clone()].iter().map(|f| f.len).collect();
    assert_eq!(lens, vec![4, 5]);
    assert!(material_of(&s, floor.faces.start).two_sided);
    assert_eq!(material_of(&s, floor.faces.start).diffuse, [0.6; 3]);
    // The tetrahedron and its USE, 5 apart in x, both closed and outward.
    let (t1, t2) = (&s.meshes[1], &s.meshes[2]);
    assert_eq!((t1.name.as_str(), t2.name.as_str()), ("tetra", "tetra"));
    assert!((closed_volume(&s, t1.faces.clone()) - 1.0 / 6.0).abs() < 1e-15);
    assert!((closed_volume(&s, t2.faces.clone()) - 1.0 / 6.0).abs() < 1e-15);
    for (f1, f2) in s.faces[t1.faces.clone()]
        .iter()
        .zip(&s.faces[t2.faces.clone()])
    {
        for (p, q) in s.face_positions(f1).zip(s.face_positions(f2)) {
            assert_eq!(q - p, DVec3::new(5.0, 0.0, 0.0));
        }
    }
    // Material USE: same colour; not two-sided (the tetra is solid).
    assert_eq!(material_of(&s, t1.faces.start).diffuse, [0.6; 3]);
    assert!(!material_of(&s, t1.faces.start).two_sided);
    // Coordinate USE with a last polygon lacking its -1; no Appearance: default grey.
    let last = &s.meshes[3];
    let lens: Vec<u32> = s.faces[last.faces.clone()].iter().map(|f| f.len).collect();
    assert_eq!(lens, vec![4, 5]);
    assert_eq!(material_of(&s, last.faces.start).diffuse, [0.8; 3]);
    assert_eq!(
        s.face_positions(&s.faces[last.faces.start]).next().unwrap(),
        DVec3::new(-4.0, -1.0, -4.0)
    );
    // The floor's TextureCoordinate is read through its coordIndex (no texCoordIndex).
    let floor_uvs: Vec<_> = s.faces[floor.faces.clone()]
        .iter()
        .map(|f| s.face_corner_uvs(f).unwrap())
        .collect();
    assert_eq!(
        floor_uvs[0],
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    assert_eq!(floor_uvs[1][4], [0.0, 0.0]);
    assert!(s.face_corner_uvs(&s.faces[t1.faces.start]).is_none());
    // One warning per unknown element, naming it and its line; the tetra's ImageTexture is not
    // applied (no TextureCoordinate), said once although the Shape is used twice.
    let w = &s.stats.warnings;
    for (name, line) in [("NavigationInfo", 4), ("ImageTexture", 21)] {
        let hits: Vec<_> = w
            .iter()
            .filter(|m| m.contains(&format!("<{name}>")))
            .collect();
        assert_eq!(hits.len(), 1, "{name}: {w:?}");
        assert!(hits[0].contains(&format!("line {line}")), "{hits:?}");
    }
    assert_eq!(w.len(), 2, "{w:?}");
    // The Background is read (its skyColor), not skipped.
    assert_eq!(s.background, Some([0.1, 0.1, 0.2]));
}

#[test]
fn colour_rule() {
    let s = x3d(r#"<Scene>
        <Shape><Appearance><Material diffuseColor="0.1 0.2 0.3"/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><Appearance><Material diffuseColor="0.1 0.2 0.3" emissiveColor="0.5 0 0"/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><Appearance><Material emissiveColor="0 0.5 0"/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><Appearance><Material transparency="0.25"/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape>
          <TriangleSet solid="false"><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><Appearance><UnlitMaterial/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><Appearance><Material diffuseColor="2 0.5 -1"/></Appearance>
          <TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        </Scene>"#);
    let m: Vec<&Material> = (0..s.faces.len()).map(|i| material_of(&s, i)).collect();
    assert_eq!((m[0].diffuse, m[0].emissive), ([0.1, 0.2, 0.3], [0.0; 3]));
    assert_eq!(
        (m[1].diffuse, m[1].emissive),
        ([0.1, 0.2, 0.3], [0.5, 0.0, 0.0])
    );
    assert_eq!((m[2].diffuse, m[2].emissive), ([0.0; 3], [0.0, 0.5, 0.0]));
    assert_eq!((m[3].diffuse, m[3].transparency), ([0.8; 3], 0.25));
    assert_eq!((m[4].diffuse, m[4].two_sided), ([0.8; 3], true));
    assert_eq!((m[5].diffuse, m[5].emissive), ([0.0; 3], [1.0; 3]));
    assert_eq!(m[6].diffuse, [1.0, 0.5, 0.0]);
    assert!(s.stats.warnings.iter().any(|w| w.contains("clamped")));
    assert_eq!(s.meshes.len(), 7);
}

#[test]
fn winding_follows_ccw_and_mirrors() {
    let s = x3d(r#"<Scene>
        <Shape><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Shape><TriangleSet ccw="false"><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
        <Transform scale="1 1 -1">
          <Shape><TriangleSet><Coordinate point="0 0 1 1 0 1 0 1 1"/></TriangleSet></Shape>
        </Transform>
        <Shape><IndexedFaceSet ccw="false" coordIndex="0 1 2 3">
          <Coordinate point="0 0 0 1 0 0 1 1 0 0 1 0"/></IndexedFaceSet></Shape>
        </Scene>"#);
    let nz: Vec<f64> = s.faces.iter().map(|f| s.face_normal(f).z).collect();
    assert!(nz[0] > 0.0 && nz[1] < 0.0, "{nz:?}");
    // The mirrored triangle, seen from -z where the mirror moved its front, stays front-facing.
    assert!(nz[2] < 0.0, "{nz:?}");
    assert!(nz[3] < 0.0, "{nz:?}");
}

#[test]
fn triangle_counts_not_multiple_of_three_drop_the_rest_with_a_warning() {
    let s = x3d(r#"<Scene>
        <Shape><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0 5 5 5"/></TriangleSet></Shape>
        <Shape><IndexedTriangleSet index="0 1 2 0 1"><Coordinate point="0 0 0 1 0 0 0 1 0"/>
        </IndexedTriangleSet></Shape></Scene>"#);
    assert_eq!(s.faces.len(), 2);
    let w = &s.stats.warnings;
    assert!(
        w.iter().any(|m| m.contains("<TriangleSet> has 4 points")),
        "{w:?}"
    );
    assert!(
        w.iter()
            .any(|m| m.contains("<IndexedTriangleSet> has 5 indices")),
        "{w:?}"
    );
}

#[test]
fn viewpoint_defaults_first_wins_and_transforms_apply() {
    let s = x3d(r#"<Scene>
        <Viewpoint/>
        <Viewpoint position="1 2 3"/>
        <Shape><Box/></Shape></Scene>"#);
    let vp = s.viewpoint.unwrap();
    assert_eq!(vp.position, DVec3::new(0.0, 0.0, 10.0));
    assert_eq!((vp.orientation_axis, vp.orientation_angle), (DVec3::Z, 0.0));
    assert_eq!(vp.field_of_view, PI / 4.0);
    assert!(
        s.stats
            .warnings
            .iter()
            .any(|w| w.contains("first <Viewpoint>"))
    );

    // Turned 90° about y and scaled: the position is transformed, the view direction only turned.
    let s = x3d(r#"<Scene>
        <Transform translation="0 1 0" rotation="0 1 0 1.5707963267948966" scale="2 2 2">
          <Viewpoint position="0 0 5" orientation="1 0 0 -0.5"/>
        </Transform>
        <Shape><Box/></Shape></Scene>"#);
    let vp = s.viewpoint.unwrap();
    assert!(
        (vp.position - DVec3::new(10.0, 1.0, 0.0)).length() < 1e-12,
        "{vp:?}"
    );
    let q = DQuat::from_axis_angle(vp.orientation_axis, vp.orientation_angle);
    let want = DQuat::from_rotation_y(FRAC_PI_2) * DQuat::from_axis_angle(DVec3::X, -0.5);
    for v in [DVec3::NEG_Z, DVec3::Y] {
        assert!(
            (q * v - want * v).length() < 1e-12,
            "{:?} vs {:?}",
            q * v,
            want * v
        );
    }
}

#[test]
fn def_use_edge_cases_do_not_crash() {
    // A USE of an enclosing group (a cycle), a USE with no DEF, a USE of another element.
    let s = x3d(r#"<Scene>
        <Group DEF="g"><Shape><Box/></Shape><Group USE="g"/></Group>
        <Shape USE="nothing"/>
        <Transform USE="g"/>
        <Group USE="g"/>
        </Scene>"#);
    // The box and the group's one good USE.
    assert_eq!(s.meshes.len(), 2);
    let w = s.stats.warnings.join("\n");
    assert!(w.contains("a cycle"), "{w}");
    assert!(w.contains("no earlier DEF"), "{w}");
    assert!(w.contains("another element"), "{w}");
}

#[test]
fn runaway_def_use_expansion_is_refused() {
    // `head` (which defines g0), then groups g1..=levels, each using the one before twice.
    let doubling = |head: &str, levels: usize| {
        let mut text = String::from(head);
        for k in 1..=levels {
            text.push_str(&format!(
                r#"<Group DEF="g{k}"><Group USE="g{}"/><Group USE="g{}"/></Group>"#,
                k - 1,
                k - 1
            ));
        }
        text + "</Scene>"
    };
    // Each level uses the previous one twice: 2^40 boxes if expanded.
    let text = doubling(
        r#"<Scene><Group DEF="g0"><Shape><Box/></Shape></Group>"#,
        40,
    );
    let t = std::time::Instant::now();
    let e = load_bytes(text.as_bytes(), Format::X3d, "bomb.x3d", None).unwrap_err();
    assert!(e.message.contains("more than"), "{e}");
    assert!(t.elapsed().as_secs() < 30);

    // The same with empty groups: bounded by the visit count.
    let text = doubling(r#"<Scene><Shape><Box/></Shape><Group DEF="g0"/>"#, 60);
    let e = load_bytes(text.as_bytes(), Format::X3d, "bomb.x3d", None).unwrap_err();
    assert!(e.message.contains("more than"), "{e}");
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let n = 100_000;
    let text = format!(
        "<Scene>{}<Shape><Box/></Shape>{}</Scene>",
        "<Group>".repeat(n),
        "</Group>".repeat(n)
    );
    let e = load_bytes(text.as_bytes(), Format::X3d, "deep.x3d", None).unwrap_err();
    assert!(e.message.contains("nested more than"), "{e}");
    // Within the limit it loads.
    let text = format!(
        "<Scene>{}<Shape><Box/></Shape>{}</Scene>",
        "<Transform translation='1 0 0'>".repeat(100),
        "</Transform>".repeat(100)
    );
    let s = x3d(&text);
    assert_eq!(s.bounds().unwrap().0.x, 99.0);
}

#[test]
fn encodings_and_doctype() {
    let text = "<?xml version=\"1.0\" encoding=\"UTF-16\"?>\n<Scene><Shape><Box/></Shape></Scene>";
    let mut le = vec![0xFF, 0xFE];
    le.extend(text.encode_utf16().flat_map(|u| u.to_le_bytes()));
    let mut be = vec![0xFE, 0xFF];
    be.extend(text.encode_utf16().flat_map(|u| u.to_be_bytes()));
    let mut bom = b"\xEF\xBB\xBF".to_vec();
    bom.extend_from_slice(b"<Scene><Shape><Box/></Shape></Scene>");
    for bytes in [le, be, bom] {
        let s = load_bytes(&bytes, Format::X3d, "enc.x3d", None).unwrap();
        assert_eq!(s.faces.len(), 6);
    }
    let s = x3d(r#"<?xml version="1.0" encoding="UTF-8"?>
<!DOCTYPE X3D PUBLIC "ISO//Web3D//DTD X3D 3.3//EN" "http://www.web3d.org/specifications/x3d-3.3.dtd">
<X3D xmlns:xsd="http://www.w3.org/2001/XMLSchema-instance" profile="Immersive" version="3.3">
<head><meta name="title" content="t"/></head>
<Scene><!-- a comment --><Shape><Box size="1,1,1"/></Shape></Scene></X3D>"#);
    assert_eq!(s.faces.len(), 6);
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
}

#[test]
fn overflowing_transforms_are_refused_or_skipped() {
    let mut b = SceneBuilder::new("t");
    let m = b.default_material();
    let huge = DMat4::from_scale(DVec3::splat(1e308));
    primitives::add_sphere(&mut b, &huge, 10.0, 8, 4, m);
    assert_eq!(b.vertex_count(), 0);
    assert!(b.stats().warnings[0].contains("non-finite"));

    let text = r#"<Scene><Transform scale="1e300 1 1"><Transform scale="1e300 1 1">
        <Shape><Box/></Shape></Transform></Transform></Scene>"#;
    let e = load_bytes(text.as_bytes(), Format::X3d, "o.x3d", None).unwrap_err();
    assert_eq!(
        e.location,
        sightline::Location::Element {
            name: "Transform".into(),
            line: 1
        },
        "{e}"
    );
    let text = r#"<Scene><Transform scale="1e300 1 1">
        <Shape><TriangleSet><Coordinate point="1e10 0 0 0 1 0 0 0 1"/></TriangleSet></Shape>
        </Transform></Scene>"#;
    let e = load_bytes(text.as_bytes(), Format::X3d, "o.x3d", None).unwrap_err();
    assert!(e.message.contains("not finite once transformed"), "{e}");
}

#[test]
fn background_is_the_first_sky_colour_or_black() {
    // No Background: X3D's default, black.
    assert_eq!(fixture("seed_transparent.x3d").background, Some([0.0; 3]));
    let s = fixture("background.x3d");
    assert_eq!(s.background, Some([0.2, 0.4, 0.6]));
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    let tri =
        r#"<Shape><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>"#;
    // A Background without skyColor is black too; a colour outside [0,1] is clamped, with a warning.
    assert_eq!(
        x3d(&format!("<Scene><Background/>{tri}</Scene>")).background,
        Some([0.0; 3])
    );
    let s = x3d(&format!(
        "<Scene><Background skyColor='2 0.5 -1'/>{tri}</Scene>"
    ));
    assert_eq!(s.background, Some([1.0, 0.5, 0.0]));
    assert!(
        s.stats.warnings.iter().any(|w| w.contains("skyColor")),
        "{:?}",
        s.stats.warnings
    );
}

#[test]
fn bad_sky_colour_names_the_background() {
    let tri =
        r#"<Shape><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>"#;
    for (sky, needle) in [
        ("0.1 x 0.3", "x"),
        ("0.1 0.2", "multiple of 3"),
        ("0 nan 0", "nan"),
    ] {
        let text = format!("<Scene>\n{tri}\n<Background\n skyColor='{sky}'/>\n</Scene>");
        let e = load_bytes(text.as_bytes(), Format::X3d, "bg.x3d", None).unwrap_err();
        assert_eq!(e.file, "bg.x3d");
        assert_eq!(
            e.location,
            Location::Element {
                name: "Background".into(),
                line: 3
            },
            "{e}"
        );
        assert!(e.message.contains("skyColor"), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
