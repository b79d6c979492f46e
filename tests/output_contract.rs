//! The README's "Output contract" and the writers agree: every JSON field the writer emits is
//! listed in the README's table of JSON fields and every listed field is emitted, the stated
//! schema and version are the writer's, and every SVG element and attribute written is listed
//! (and every listed attribute written by some render). The contract cannot drift silently.

use sightline::output::json::{SCHEMA, VERSION};
use std::collections::BTreeSet;
use std::process::Command;

/// What `sightline render INPUT -o OUT --size 48x36 FLAGS...` writes to OUT.
fn render(input: &str, out: &str, flags: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(out);
    let o = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["render", input, "--size", "48x36", "-o"])
        .arg(&path)
        .args(flags)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(&path).unwrap()
}

/// The lines of the README section that starts with `heading`, up to the next heading.
fn readme_section(heading: &str) -> Vec<String> {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let lines: Vec<&str> = readme.lines().collect();
    let start = lines
        .iter()
        .position(|l| *l == heading)
        .unwrap_or_else(|| panic!("README.md has no section {heading:?}"));
    lines[start + 1..]
        .iter()
        .take_while(|l| !l.starts_with('#'))
        .map(|l| l.to_string())
        .collect()
}

/// The cells of the table rows of a section (header and rule excluded).
fn table_rows(section: &[String]) -> Vec<Vec<String>> {
    section
        .iter()
        .filter(|l| l.starts_with('|') && !l.starts_with("|---"))
        .skip(1)
        .map(|l| {
            l.trim_matches('|')
                .split(" | ")
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}

/// The `code` spans of a table cell.
fn code_spans(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The field paths of a JSON document: `key` at the top, `parent[].key` in the objects of an
/// array, `parent.key` in an object. `stats` is free-form: its keys are not fields.
fn field_paths(v: &serde_json::Value, prefix: &str, out: &mut BTreeSet<String>) {
    match v {
        serde_json::Value::Object(map) => {
            for (k, child) in map {
                let path = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                out.insert(path.clone());
                if path != "stats" {
                    field_paths(child, &path, out);
                }
            }
        }
        serde_json::Value::Array(items) => {
            for item in items.iter().filter(|i| i.is_object()) {
                field_paths(item, &format!("{prefix}[]"), out);
            }
        }
        _ => {}
    }
}

const JSON_FIELDS: &str = "### JSON fields";
const SVG_ATTRIBUTES: &str = "### SVG elements and attributes";

#[test]
fn json_fields_are_exactly_the_readme_contract() {
    let listed: BTreeSet<String> = table_rows(&readme_section(JSON_FIELDS))
        .iter()
        .map(|row| code_spans(&row[0]).concat())
        .collect();
    let mut emitted = BTreeSet::new();
    // An opaque and a translucent material, and the painter's output.
    for (input, flags) in [
        ("fixtures/cube.obj", &[][..]),
        ("fixtures/cyclic_bars.obj", &["--method", "painter"][..]),
    ] {
        let text = render(input, "out.json", flags);
        let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
        field_paths(&doc, "", &mut emitted);
    }
    let unlisted: Vec<&String> = emitted.difference(&listed).collect();
    let missing: Vec<&String> = listed.difference(&emitted).collect();
    assert!(
        unlisted.is_empty(),
        "the JSON writer emits fields that README.md's {JSON_FIELDS:?} does not list: {unlisted:?}"
    );
    assert!(
        missing.is_empty(),
        "README.md's {JSON_FIELDS:?} lists fields the JSON writer does not emit: {missing:?}"
    );
}

#[test]
fn json_starts_with_the_schema_and_version_the_readme_states() {
    let text = render("fixtures/cube.obj", "out.json", &[]);
    assert!(
        text.starts_with(&format!(
            "{{\n  \"schema\": \"{SCHEMA}\",\n  \"version\": {VERSION},\n  \"width\": 48,"
        )),
        "{}",
        &text[..text.len().min(200)]
    );
    let section = readme_section(JSON_FIELDS).join("\n");
    assert!(
        section.contains(&format!("Version {VERSION}.")),
        "README.md's {JSON_FIELDS:?} states another version than {VERSION}"
    );
    assert!(
        section.contains(&format!("always `\"{SCHEMA}\"`")),
        "README.md's {JSON_FIELDS:?} states another schema than {SCHEMA}"
    );
}

/// (element, attribute) of every start tag in an SVG document, namespace declarations included.
fn svg_attributes(svg: &str) -> BTreeSet<(String, String)> {
    let mut out = BTreeSet::new();
    for tag in svg.split('<').skip(1) {
        if tag.starts_with('/') {
            continue;
        }
        let tag = &tag[..tag.find('>').unwrap()];
        let name = tag.split([' ', '/']).next().unwrap().to_string();
        // Attribute values hold no `="`, so every `="` ends an attribute name.
        for piece in tag.split("=\"").collect::<Vec<_>>().split_last().unwrap().1 {
            let attr = piece.rsplit(' ').next().unwrap();
            out.insert((name.clone(), attr.to_string()));
        }
    }
    out
}

#[test]
fn svg_elements_and_attributes_are_exactly_the_readme_contract() {
    let rows = table_rows(&readme_section(SVG_ATTRIBUTES));
    let elements: BTreeSet<String> = rows
        .iter()
        .flat_map(|row| code_spans(&row[0]))
        .flat_map(|c| {
            let tag = c.trim_matches(['<', '>']).to_string();
            (c.starts_with('<')).then_some(tag)
        })
        .collect();
    let listed: BTreeSet<String> = rows.iter().flat_map(|row| code_spans(&row[1])).collect();
    let mut written = BTreeSet::new();
    // Seams, translucency, outlines and crisp edges; then surfaces merged across faces.
    for (input, flags) in [
        ("fixtures/cube.obj", &["--stroke", "--crisp"][..]),
        ("fixtures/t_junction.obj", &[][..]),
    ] {
        written.extend(svg_attributes(&render(input, "out.svg", flags)));
    }
    for (element, attribute) in &written {
        assert!(
            elements.contains(element),
            "<{element}> is written but not listed in README.md's {SVG_ATTRIBUTES:?}"
        );
        assert!(
            listed.contains(attribute),
            "{attribute} (on <{element}>) is written but not listed in README.md's \
             {SVG_ATTRIBUTES:?}"
        );
    }
    let attributes: BTreeSet<String> = written.into_iter().map(|(_, a)| a).collect();
    let missing: Vec<&String> = listed.difference(&attributes).collect();
    assert!(
        missing.is_empty(),
        "README.md's {SVG_ATTRIBUTES:?} lists attributes no render writes: {missing:?}"
    );
}

/// Twice the signed area of a ring on its numbers, `Σ (x_i·y_{i+1} - x_{i+1}·y_i)`.
fn twice_area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| ring[i][0] * ring[(i + 1) % n][1] - ring[(i + 1) % n][0] * ring[i][1])
        .sum()
}

#[test]
fn written_regions_are_in_the_canonical_form_the_readme_states() {
    for (input, flags) in [
        ("fixtures/interpenetrating.obj", &[][..]),
        ("fixtures/cyclic_bars.obj", &["--method", "painter"][..]),
    ] {
        let doc: serde_json::Value =
            serde_json::from_str(&render(input, "out.json", flags)).unwrap();
        let mut places = Vec::new();
        for face in doc["faces"].as_array().unwrap() {
            let regions: Vec<Vec<Vec<[f64; 2]>>> =
                serde_json::from_value(face["regions"].clone()).unwrap();
            for rings in regions {
                // A region's first ring is an outer one: it starts at the region's top-left
                // vertex, with a positive area on the numbers.
                for (k, ring) in rings.iter().enumerate() {
                    let top_left = ring
                        .iter()
                        .min_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])))
                        .unwrap();
                    assert_eq!(&ring[0], top_left, "{input}: face {}", face["id"]);
                    if k == 0 {
                        assert!(twice_area(ring) > 0.0, "{input}: face {}", face["id"]);
                    }
                }
            }
            places.extend(
                face["draw_order"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|p| p.as_u64().unwrap()),
            );
        }
        places.sort_unstable();
        assert!(
            places.iter().enumerate().all(|(k, &p)| p == k as u64),
            "{input}: {places:?}"
        );
    }
}
