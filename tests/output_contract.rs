//! The README's "Output contract" and the writers agree: every JSON field a writer emits is
//! listed in the README's table of its JSON fields and every listed field is emitted, the stated
//! schema and version are the writer's, and every SVG element and attribute written is listed
//! (and every listed attribute written by some render). The same holds for the line drawings
//! of `lines` (and their classes). The contract cannot drift silently.

use sightline::lines::{LineKind, Visibility};
use sightline::output::json::{SCHEMA, VERSION};
use sightline::output::line_json;
use std::collections::BTreeSet;
use std::process::Command;

/// What `sightline COMMAND INPUT -o OUT --size 48x36 FLAGS...` writes to OUT.
fn run(command: &str, input: &str, out: &str, flags: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(out);
    let o = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args([command, input, "--size", "48x36", "-o"])
        .arg(&path)
        .args(flags)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(&path).unwrap()
}

/// What `sightline render INPUT -o OUT --size 48x36 FLAGS...` writes to OUT.
fn render(input: &str, out: &str, flags: &[&str]) -> String {
    run("render", input, out, flags)
}

/// What `sightline lines INPUT -o OUT --size 48x36 FLAGS...` writes to OUT.
fn lines(input: &str, out: &str, flags: &[&str]) -> String {
    run("lines", input, out, flags)
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
const LINE_JSON_FIELDS: &str = "### Line JSON fields";
const LINE_SVG_ATTRIBUTES: &str = "### Line SVG elements and attributes";

/// The field paths of the JSON documents `texts` are exactly those `section` lists.
fn assert_json_fields_are_listed(section: &str, texts: &[String]) {
    let listed: BTreeSet<String> = table_rows(&readme_section(section))
        .iter()
        .map(|row| code_spans(&row[0]).concat())
        .collect();
    let mut emitted = BTreeSet::new();
    for text in texts {
        let doc: serde_json::Value = serde_json::from_str(text).unwrap();
        field_paths(&doc, "", &mut emitted);
    }
    let unlisted: Vec<&String> = emitted.difference(&listed).collect();
    let missing: Vec<&String> = listed.difference(&emitted).collect();
    assert!(
        unlisted.is_empty(),
        "the JSON writer emits fields that README.md's {section:?} does not list: {unlisted:?}"
    );
    assert!(
        missing.is_empty(),
        "README.md's {section:?} lists fields the JSON writer does not emit: {missing:?}"
    );
}

/// `text` starts with `schema` and `version` as its first keys and a width of 48, and
/// `section` states both.
fn assert_schema_and_version(section: &str, text: &str, schema: &str, version: u32) {
    assert!(
        text.starts_with(&format!(
            "{{\n  \"schema\": \"{schema}\",\n  \"version\": {version},\n  \"width\": 48,"
        )),
        "{}",
        &text[..text.len().min(200)]
    );
    let section_text = readme_section(section).join("\n");
    assert!(
        section_text.contains(&format!("Version {version}")),
        "README.md's {section:?} states another version than {version}"
    );
    assert!(
        section_text.contains(&format!("always `\"{schema}\"`")),
        "README.md's {section:?} states another schema than {schema}"
    );
}

#[test]
fn json_fields_are_exactly_the_readme_contract() {
    // An opaque and a translucent material, and the painter's output.
    let texts = [
        render("fixtures/cube.obj", "out.json", &[]),
        render(
            "fixtures/cyclic_bars.obj",
            "out.json",
            &["--method", "painter"],
        ),
    ];
    assert_json_fields_are_listed(JSON_FIELDS, &texts);
}

#[test]
fn json_starts_with_the_schema_and_version_the_readme_states() {
    let text = render("fixtures/cube.obj", "out.json", &[]);
    assert_schema_and_version(JSON_FIELDS, &text, SCHEMA, VERSION);
    // The version is stated as a sentence of its own.
    let section = readme_section(JSON_FIELDS).join("\n");
    assert!(section.contains(&format!("Version {VERSION}.")));
}

#[test]
fn line_json_fields_are_exactly_the_readme_contract() {
    let texts = [lines("fixtures/cube.obj", "out.json", &[])];
    assert_json_fields_are_listed(LINE_JSON_FIELDS, &texts);
    assert_schema_and_version(
        LINE_JSON_FIELDS,
        &texts[0],
        line_json::SCHEMA,
        line_json::VERSION,
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

/// Every element and attribute of the SVG documents `svgs` is listed in `section`'s table, and
/// every attribute listed there is written by one of them.
fn assert_svg_attributes_are_listed(section: &str, svgs: &[String]) {
    let rows = table_rows(&readme_section(section));
    let elements: BTreeSet<String> = rows
        .iter()
        .flat_map(|row| code_spans(&row[0]))
        .flat_map(|c| {
            let tag = c.trim_matches(['<', '>']).to_string();
            (c.starts_with('<')).then_some(tag)
        })
        .collect();
    let listed: BTreeSet<String> = rows.iter().flat_map(|row| code_spans(&row[1])).collect();
    let written: BTreeSet<(String, String)> =
        svgs.iter().flat_map(|svg| svg_attributes(svg)).collect();
    let written_elements: BTreeSet<String> = svgs
        .iter()
        .flat_map(|svg| svg.split('<').skip(1).filter(|t| !t.starts_with('/')))
        .map(|t| t.split([' ', '/', '>']).next().unwrap().to_string())
        .collect();
    for element in &written_elements {
        assert!(
            elements.contains(element),
            "<{element}> is written but not listed in README.md's {section:?}"
        );
    }
    for (element, attribute) in &written {
        assert!(
            listed.contains(attribute),
            "{attribute} (on <{element}>) is written but not listed in README.md's {section:?}"
        );
    }
    let attributes: BTreeSet<String> = written.into_iter().map(|(_, a)| a).collect();
    let missing: Vec<&String> = listed.difference(&attributes).collect();
    assert!(
        missing.is_empty(),
        "README.md's {section:?} lists attributes no render writes: {missing:?}"
    );
}

#[test]
fn svg_elements_and_attributes_are_exactly_the_readme_contract() {
    // Seams, translucency, outlines and crisp edges; then surfaces merged across faces.
    let svgs = [
        render("fixtures/cube.obj", "out.svg", &["--stroke", "--crisp"]),
        render("fixtures/t_junction.obj", "out.svg", &[]),
    ];
    assert_svg_attributes_are_listed(SVG_ATTRIBUTES, &svgs);
}

#[test]
fn line_svg_elements_and_attributes_are_exactly_the_readme_contract() {
    let svg = lines(
        "fixtures/cube.obj",
        "out.svg",
        &["--background", "255,255,255"],
    );
    assert_svg_attributes_are_listed(LINE_SVG_ATTRIBUTES, std::slice::from_ref(&svg));
    // What `render --lines` adds to the filled drawing is listed there too.
    let overlaid = render("fixtures/cube.obj", "out.svg", &["--lines"]);
    let plain = render("fixtures/cube.obj", "out.svg", &[]);
    let added = overlaid
        .strip_prefix(plain.trim_end().trim_end_matches("</svg>"))
        .expect("the overlay adds to the end of the filled drawing");
    let added = format!("<svg>{added}");
    let attributes = svg_attributes(&added);
    assert!(attributes.contains(&("g".into(), "class".into())));
    let listed: BTreeSet<String> = table_rows(&readme_section(LINE_SVG_ATTRIBUTES))
        .iter()
        .flat_map(|row| code_spans(&row[1]))
        .collect();
    for (element, attribute) in attributes {
        assert!(
            listed.contains(&attribute),
            "<{element} {attribute}> not listed"
        );
    }
}

#[test]
fn line_svg_classes_are_the_words_the_readme_states() {
    let rows = table_rows(&readme_section(LINE_SVG_ATTRIBUTES));
    let group = rows
        .iter()
        .find(|row| row[0] == "`<g>`")
        .expect("the README lists <g>");
    let words: BTreeSet<String> = code_spans(&group[2]).into_iter().collect();
    // Every visibility and kind the library has is stated, in the stated order.
    let names: Vec<&str> = [Visibility::Visible, Visibility::Hidden]
        .iter()
        .map(|v| v.name())
        .chain(LineKind::ALL.iter().map(|k| k.name()))
        .collect();
    for name in &names {
        assert!(words.contains(*name), "README.md's <g> row omits {name:?}");
    }
    let stated: Vec<&str> = group[2]
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|w| names.contains(w))
        .collect();
    assert_eq!(stated, names, "README.md's <g> row states another order");
    // Every class written is a visibility and a kind.
    let svg = lines("fixtures/interpenetrating.obj", "out.svg", &[]);
    let classes: Vec<&str> = svg
        .split("class=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    assert!(!classes.is_empty());
    for class in classes {
        let parts: Vec<&str> = class.split(' ').collect();
        assert!(
            parts.len() == 2 && names[..2].contains(&parts[0]) && names[2..].contains(&parts[1]),
            "class {class:?}"
        );
    }
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
