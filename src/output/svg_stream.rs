//! An SVG document written element by element as it is made, never held whole in memory.
//!
//! The `svg` crate formats every element (attributes sorted by name, values escaped); this
//! module only nests them: an element is opened, its children follow, it is closed. The bytes
//! are those the crate's own document tree prints (`Document::to_string`): a child follows its
//! parent's opening tag on a new line, a closing tag follows the last child on a new line, and
//! an element that gets no child is written self-closing (`<g/>`). So a drawing streamed here
//! and one built as a tree are the same file, and only the text of what is being written exists
//! at a time.

use ::svg::Node;
use ::svg::node::element::Element;
use std::io::{self, Write};

/// The writer. Open elements with [`Self::open`], add children with [`Self::child`], close
/// them with [`Self::close`]; [`Self::finish`] closes what is open and ends the file.
pub struct SvgStream<'w> {
    out: &'w mut dyn Write,
    /// The open elements, outermost first: each one's name, and its opening tag while it has
    /// no child yet (written when the first child comes, or self-closing at its close).
    open: Vec<(String, Option<String>)>,
}

impl<'w> SvgStream<'w> {
    /// A document on `out` whose root is `root` (an `svg::Document`, with its attributes and no
    /// children).
    pub fn new(out: &'w mut dyn Write, root: impl Into<Element>) -> SvgStream<'w> {
        let mut s = SvgStream {
            out,
            open: Vec::new(),
        };
        s.push(root.into());
        s
    }

    /// Opens `element` (its attributes; children come next) inside the current element.
    pub fn open(&mut self, element: impl Into<Element>) -> io::Result<()> {
        self.start_child()?;
        self.push(element.into());
        Ok(())
    }

    /// Writes `node`, whole, as the next child of the current element.
    pub fn child(&mut self, node: impl Node) -> io::Result<()> {
        self.start_child()?;
        write!(self.out, "{node}")
    }

    /// Writes the element `<name a="v" .../>`, with no children, as the next child of the
    /// current element: the bytes [`Self::child`] writes for the crate's element with these
    /// attributes (sorted by name, values escaped as the crate escapes them), without building
    /// it (a hash map of attribute strings, and five copies of each value to escape it: most of
    /// the time of writing a drawing of many paths). Attribute names are distinct.
    pub fn leaf(&mut self, name: &str, attributes: &mut [(&str, &str)]) -> io::Result<()> {
        self.start_child()?;
        write_leaf(self.out, name, attributes)
    }

    /// Writes children made by [`render_leaf`] (any number, one after another in `rendered`)
    /// as the next children of the current element: the bytes [`Self::leaf`] writes for each.
    /// So leaves can be rendered on all cores and written in order.
    pub fn rendered_leaves(&mut self, rendered: &[u8]) -> io::Result<()> {
        if rendered.is_empty() {
            return Ok(());
        }
        self.open_tag()?;
        self.out.write_all(rendered)
    }

    /// Closes the current element.
    pub fn close(&mut self) -> io::Result<()> {
        let (name, pending) = self.open.pop().expect("an open element");
        match pending {
            // No child: the crate writes it self-closing.
            Some(tag) => self.out.write_all(tag.as_bytes()),
            None => write!(self.out, "\n</{name}>"),
        }
    }

    /// Closes every open element and ends the file with a newline.
    pub fn finish(mut self) -> io::Result<()> {
        while !self.open.is_empty() {
            self.close()?;
        }
        self.out.write_all(b"\n")
    }

    fn push(&mut self, element: Element) {
        let name = element.get_name().to_string();
        // An element without children prints self-closing: that is its opening tag but for
        // the end.
        let tag = element.to_string();
        debug_assert!(tag.ends_with("/>"), "{tag}: opened with children");
        self.open.push((name, Some(tag)));
    }

    /// Writes the current element's opening tag if no child has, then the new line a child
    /// starts on.
    fn start_child(&mut self) -> io::Result<()> {
        self.open_tag()?;
        self.out.write_all(b"\n")
    }

    /// Writes the current element's opening tag if no child has.
    fn open_tag(&mut self) -> io::Result<()> {
        let (_, pending) = self.open.last_mut().expect("an open element");
        if let Some(tag) = pending.take() {
            let open = tag.strip_suffix("/>").expect("self-closing");
            write!(self.out, "{open}>")?;
        }
        Ok(())
    }
}

/// Appends to `rendered` a child leaf as [`SvgStream::leaf`] writes it (the new line it starts
/// on, then the element), for [`SvgStream::rendered_leaves`].
pub fn render_leaf(rendered: &mut Vec<u8>, name: &str, attributes: &mut [(&str, &str)]) {
    rendered.push(b'\n');
    write_leaf(rendered, name, attributes).expect("writing into memory cannot fail");
}

/// The element `<name a="v" .../>` (see [`SvgStream::leaf`]).
fn write_leaf(out: &mut dyn Write, name: &str, attributes: &mut [(&str, &str)]) -> io::Result<()> {
    attributes.sort_unstable_by_key(|a| a.0);
    debug_assert!(attributes.windows(2).all(|w| w[0].0 != w[1].0));
    out.write_all(b"<")?;
    out.write_all(name.as_bytes())?;
    for (key, value) in attributes.iter() {
        out.write_all(b" ")?;
        out.write_all(key.as_bytes())?;
        out.write_all(b"=\"")?;
        write_escaped(out, value)?;
        out.write_all(b"\"")?;
    }
    out.write_all(b"/>")
}

/// `value` as the crate writes an attribute value: `&`, `<`, `>`, `"` and `'` as entities
/// (one pass; the crate replaces them one after the other, `&` first, which comes to the same).
fn write_escaped(out: &mut dyn Write, value: &str) -> io::Result<()> {
    let bytes = value.as_bytes();
    // Most values (path data, colours) have nothing to escape: looked for in one pass
    // without an early exit, which the compiler runs many bytes at a time.
    if !bytes
        .iter()
        .fold(false, |any, &b| any | entity(b).is_some())
    {
        return out.write_all(bytes);
    }
    let mut plain = 0;
    for (i, &b) in bytes.iter().enumerate() {
        let Some(entity) = entity(b) else {
            continue;
        };
        out.write_all(&bytes[plain..i])?;
        out.write_all(entity)?;
        plain = i + 1;
    }
    out.write_all(&bytes[plain..])
}

/// The entity an attribute value writes for byte `b`, if any.
fn entity(b: u8) -> Option<&'static [u8]> {
    Some(match b {
        b'&' => b"&amp;",
        b'<' => b"&lt;",
        b'>' => b"&gt;",
        b'"' => b"&quot;",
        b'\'' => b"&apos;",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::svg::Document;
    use ::svg::node::element::{ClipPath, Definitions, Group, Path, Rectangle, Style};

    #[test]
    fn a_streamed_document_has_the_bytes_of_the_crates_tree() {
        let path = |d: &str| Path::new().set("d", d).set("fill", "#102030");
        let doc = Document::new().set("viewBox", "0 0 4 3").set("width", 4);
        let tree = doc
            .clone()
            .add(Rectangle::new().set("width", 4).set("fill", "#ffffff"))
            .add(Definitions::new().add(ClipPath::new().set("id", "c").add(path("M0 0L1 1Z"))))
            .add(Group::new().set("clip-path", "url(#c)"))
            .add(Group::new().add(path("M1 2L3 4Z")).add(path("M5 6L7 8Z")))
            .add(Style::new(".a{fill:none} b > c & d"));
        let mut streamed = Vec::new();
        let mut s = SvgStream::new(&mut streamed, doc);
        s.child(Rectangle::new().set("width", 4).set("fill", "#ffffff"))
            .unwrap();
        s.open(Definitions::new()).unwrap();
        s.open(ClipPath::new().set("id", "c")).unwrap();
        s.child(path("M0 0L1 1Z")).unwrap();
        s.close().unwrap();
        s.close().unwrap();
        // Opened and closed with no child: self-closing, as the tree prints it.
        s.open(Group::new().set("clip-path", "url(#c)")).unwrap();
        s.close().unwrap();
        s.open(Group::new()).unwrap();
        s.child(path("M1 2L3 4Z")).unwrap();
        s.child(path("M5 6L7 8Z")).unwrap();
        s.close().unwrap();
        s.child(Style::new(".a{fill:none} b > c & d")).unwrap();
        s.finish().unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), format!("{tree}\n"));
    }

    /// Leaves written directly are the crate's elements, byte for byte: attributes in any
    /// order, values with every character the crate escapes, next to each other and alone.
    #[test]
    fn a_leaf_has_the_bytes_of_the_crates_element() {
        let values = [
            "M0 0L1 1Z",
            "",
            "&",
            "a<b>c\"d'e&f",
            "&amp;&&lt;",
            "''\"\"<<>>",
            "é ü — ∑",
        ];
        for (k, value) in values.iter().enumerate() {
            let other = values[(k + 3) % values.len()];
            let mut attributes = [
                ("fill-rule", "evenodd"),
                ("d", *value),
                ("data-face", other),
                ("fill", "#102030"),
            ];
            let mut element = Path::new();
            for (name, v) in attributes {
                element = element.set(name, v);
            }
            let doc = Document::new().set("width", 1);
            let mut by_crate = Vec::new();
            let mut s = SvgStream::new(&mut by_crate, doc.clone());
            s.child(element).unwrap();
            s.finish().unwrap();
            let mut direct = Vec::new();
            let mut s = SvgStream::new(&mut direct, doc.clone());
            s.leaf("path", &mut attributes).unwrap();
            s.finish().unwrap();
            let by_crate = String::from_utf8(by_crate).unwrap();
            assert_eq!(String::from_utf8(direct).unwrap(), by_crate);
            // Rendered apart and written later: the same bytes.
            let mut rendered = Vec::new();
            render_leaf(&mut rendered, "path", &mut attributes);
            let mut later = Vec::new();
            let mut s = SvgStream::new(&mut later, doc);
            s.rendered_leaves(&rendered).unwrap();
            s.finish().unwrap();
            assert_eq!(String::from_utf8(later).unwrap(), by_crate);
        }
    }

    /// Several leaves rendered into one buffer, and an empty one, are the leaves written one by
    /// one: an element given no leaf stays self-closing.
    #[test]
    fn rendered_leaves_are_leaves_written_one_by_one() {
        let doc = Document::new().set("width", 1);
        let leaves = [("d", "M0 0Z"), ("d", "M1 1Z"), ("fill", "#000000")];
        let mut one_by_one = Vec::new();
        let mut s = SvgStream::new(&mut one_by_one, doc.clone());
        s.open(Group::new()).unwrap();
        s.close().unwrap();
        s.open(Group::new()).unwrap();
        for a in leaves {
            s.leaf("path", &mut [a]).unwrap();
        }
        s.finish().unwrap();
        let render = |leaves: &[(&str, &str)]| {
            let mut rendered = Vec::new();
            for &a in leaves {
                render_leaf(&mut rendered, "path", &mut [a]);
            }
            rendered
        };
        let mut batched = Vec::new();
        let mut s = SvgStream::new(&mut batched, doc);
        s.open(Group::new()).unwrap();
        s.rendered_leaves(&[]).unwrap();
        s.close().unwrap();
        s.open(Group::new()).unwrap();
        s.rendered_leaves(&render(&leaves[..1])).unwrap();
        s.rendered_leaves(&render(&leaves[1..])).unwrap();
        s.finish().unwrap();
        let text = String::from_utf8(batched).unwrap();
        assert_eq!(text, String::from_utf8(one_by_one).unwrap());
        assert!(text.contains("<g/>"), "{text}");
    }

    #[test]
    fn an_empty_document_is_self_closing() {
        let doc = Document::new().set("width", 1);
        let mut streamed = Vec::new();
        SvgStream::new(&mut streamed, doc.clone()).finish().unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), format!("{doc}\n"));
    }
}
