//! MTL material libraries for OBJ.
//!
//! Guarantees of the returned materials: every colour component and the transparency are finite
//! and in [0, 1] (values outside are clamped, with a warning naming the file and line).
//!
//! Read: `newmtl NAME`, `Kd r [g b]` (diffuse), `Ke r [g b]` (emissive), `d x` (transparency
//! 1 - x, `-halo` accepted and ignored) and `Tr x` (transparency x); when a material has both `d`
//! and `Tr` the later statement wins. Other standard statements (`Ka`, `Ks`, `Ns`, `illum`,
//! `map_*` other than `map_Kd`, ...) are ignored silently since they do not change what a face looks like here;
//! unknown ones get one warning per keyword. `Kd spectral` / `Kd xyz` get a warning and are
//! ignored. `map_Kd [options] FILE` names the diffuse texture: the options of the MTL
//! specification (`-blendu`, `-blendv`, `-cc`, `-clamp`, `-boost`, `-texres`, `-bm`, `-imfchan`,
//! `-type` with one value, `-mm` with two, `-o`, `-s`, `-t` with one to three numbers) are skipped,
//! not applied, and the rest of the line is the file name (it may hold spaces). `map_Kd` with no
//! file name after its options is an error. Errors (bad or non-finite numbers, wrong value
//! counts, a texture without a file) name the `.mtl` file and line. Lines may end in `\r\n`; a
//! leading UTF-8 byte-order mark is skipped.

use super::Material;
use super::input::BOM;
use super::text::{Tokens, lossy, next_line, parse_f64, show, strip_comment};
use crate::error::LoadError;

/// Parses a material library. `file` names it in errors and warnings.
#[cfg(test)]
pub(super) fn parse(
    bytes: &[u8],
    file: &str,
    warnings: &mut Vec<String>,
) -> Result<Vec<Material>, LoadError> {
    Ok(parse_with_textures(bytes, file, warnings)?.0)
}

/// A material's `map_Kd` file name as written, if it has one.
pub(super) type TextureName = Option<Vec<u8>>;

/// [`parse`], also returning each material's `map_Kd` file name (raw bytes, as written).
pub(super) fn parse_with_textures(
    bytes: &[u8],
    file: &str,
    warnings: &mut Vec<String>,
) -> Result<(Vec<Material>, Vec<TextureName>), LoadError> {
    let mut out: Vec<Material> = Vec::new();
    let mut textures: Vec<TextureName> = Vec::new();
    let mut unknown_seen: Vec<Vec<u8>> = Vec::new();
    let mut warned_orphan = false;
    // A byte-order mark is not part of the first statement.
    let mut pos = if bytes.starts_with(BOM) { BOM.len() } else { 0 };
    let mut line = 0;
    while pos < bytes.len() {
        let (raw, next) = next_line(bytes, pos);
        pos = next;
        line += 1;
        let mut toks = Tokens::new(strip_comment(raw));
        let Some(kw) = toks.next() else { continue };
        if kw == b"newmtl" {
            let name = lossy(toks.rest()).into_owned();
            if name.is_empty() {
                return Err(LoadError::line(file, line, "newmtl without a name"));
            }
            out.push(Material {
                name,
                ..Material::default()
            });
            textures.push(None);
            continue;
        }
        if kw == b"map_Kd" {
            let Some(name) = texture_file(toks) else {
                return Err(LoadError::line(file, line, "map_Kd without a file name"));
            };
            match textures.last_mut() {
                Some(t) => *t = Some(name.to_vec()),
                None => warnings.push(format!("{file}:{line}: 'map_Kd' before any newmtl ignored")),
            }
            continue;
        }
        let known = matches!(kw, b"Kd" | b"Ke" | b"d" | b"Tr");
        let ignored = matches!(
            kw,
            b"Ka"
                | b"Ks"
                | b"Ns"
                | b"Ni"
                | b"illum"
                | b"Tf"
                | b"sharpness"
                | b"bump"
                | b"disp"
                | b"decal"
                | b"refl"
                | b"norm"
                | b"Pr"
                | b"Pm"
                | b"Ps"
                | b"Pc"
                | b"Pcr"
                | b"aniso"
                | b"anisor"
        ) || kw.starts_with(b"map_");
        if !known {
            if !ignored && !unknown_seen.iter().any(|k| k == kw) {
                unknown_seen.push(kw.to_vec());
                warnings.push(format!(
                    "{file}:{line}: unsupported statement '{}' ignored (reported once)",
                    show(kw)
                ));
            }
            continue;
        }
        let Some(m) = out.last_mut() else {
            if !warned_orphan {
                warned_orphan = true;
                warnings.push(format!(
                    "{file}:{line}: '{}' before any newmtl ignored",
                    show(kw)
                ));
            }
            continue;
        };
        match kw {
            b"Kd" | b"Ke" => {
                let what = if kw == b"Kd" { "Kd" } else { "Ke" };
                if let Some(first) = toks.clone().next()
                    && (first == b"spectral" || first == b"xyz")
                {
                    warnings.push(format!(
                        "{file}:{line}: '{what} {}' is not supported; ignored",
                        show(first)
                    ));
                    continue;
                }
                let vals = numbers::<3>(toks, file, line, what)?;
                let rgb = match vals {
                    (1, [r, ..]) => [r, r, r],
                    (3, v) => v,
                    (n, _) => {
                        return Err(LoadError::line(
                            file,
                            line,
                            format!("{what} needs 1 or 3 values, found {n}"),
                        ));
                    }
                };
                let mut c = [0.0; 3];
                for (dst, v) in c.iter_mut().zip(rgb) {
                    *dst = clamp01(v, what, file, line, warnings);
                }
                if kw == b"Kd" {
                    m.diffuse = c;
                } else {
                    m.emissive = c;
                }
            }
            _ => {
                let is_d = kw == b"d";
                let what = if is_d { "d" } else { "Tr" };
                let mut rest = toks.clone();
                if is_d && rest.next() == Some(&b"-halo"[..]) {
                    toks = rest;
                }
                let (n, [x, ..]) = numbers::<1>(toks, file, line, what)?;
                if n != 1 {
                    return Err(LoadError::line(
                        file,
                        line,
                        format!("{what} needs 1 value, found {n}"),
                    ));
                }
                let x = clamp01(x, what, file, line, warnings);
                m.transparency = if is_d { 1.0 - x } else { x };
            }
        }
    }
    Ok((out, textures))
}

/// The file name of a texture statement after its options (see the module docs), `None` when
/// nothing is left.
fn texture_file<'a>(mut toks: Tokens<'a>) -> Option<&'a [u8]> {
    loop {
        let mut after = toks.clone();
        let arity = match after.next()? {
            b"-blendu" | b"-blendv" | b"-cc" | b"-clamp" | b"-boost" | b"-texres" | b"-bm"
            | b"-imfchan" | b"-type" => 1,
            b"-mm" => 2,
            b"-o" | b"-s" | b"-t" => {
                // One to three numbers: the first is required, the others only if numeric.
                after.next()?;
                for _ in 0..2 {
                    let mut peek = after.clone();
                    if peek.next().and_then(parse_f64).is_some() {
                        after = peek;
                    }
                }
                0
            }
            _ => {
                let rest = toks.rest();
                return (!rest.is_empty()).then_some(rest);
            }
        };
        for _ in 0..arity {
            after.next()?;
        }
        toks = after;
    }
}

/// Reads up to `N` finite numbers; returns how many tokens there were (more than `N` is reported
/// as `N + 1`) and the values.
fn numbers<const N: usize>(
    toks: Tokens,
    file: &str,
    line: usize,
    what: &str,
) -> Result<(usize, [f64; N]), LoadError> {
    let mut vals = [0.0; N];
    let mut n = 0;
    for t in toks {
        if n == N {
            return Ok((N + 1, vals));
        }
        let x = match parse_f64(t) {
            Some(x) if x.is_finite() => x,
            Some(_) => {
                return Err(LoadError::line(
                    file,
                    line,
                    format!("{what} value '{}' is not finite", show(t)),
                ));
            }
            None => {
                return Err(LoadError::line(
                    file,
                    line,
                    format!("bad number '{}' in {what}", show(t)),
                ));
            }
        };
        vals[n] = x;
        n += 1;
    }
    Ok((n, vals))
}

fn clamp01(x: f64, what: &str, file: &str, line: usize, warnings: &mut Vec<String>) -> f64 {
    if (0.0..=1.0).contains(&x) {
        x
    } else {
        let c = x.clamp(0.0, 1.0);
        warnings.push(format!(
            "{file}:{line}: {what} value {x} outside [0, 1], clamped to {c}"
        ));
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Location;

    fn parse_str(s: &str) -> (Result<Vec<Material>, LoadError>, Vec<String>) {
        let mut w = Vec::new();
        let r = parse(s.as_bytes(), "t.mtl", &mut w);
        (r, w)
    }

    #[test]
    fn reads_colours_and_transparency() {
        let (m, w) = parse_str(
            "# lib\nnewmtl red\nKd 1 0 0\nKa 0.1 0.1 0.1\nd 0.75\n\nnewmtl glow\r\nKd 0.5\nKe 0 1 0\nd 0.2\nTr 0.3\nnewmtl halo\nd -halo 0.4\n",
        );
        let m = m.unwrap();
        assert!(w.is_empty(), "{w:?}");
        assert_eq!(m.len(), 3);
        assert_eq!(m[0].name, "red");
        assert_eq!(m[0].diffuse, [1.0, 0.0, 0.0]);
        assert_eq!(m[0].transparency, 0.25);
        assert_eq!(m[1].diffuse, [0.5; 3]);
        assert_eq!(m[1].emissive, [0.0, 1.0, 0.0]);
        assert_eq!(m[1].transparency, 0.3, "the later of d and Tr wins");
        assert!((m[2].transparency - 0.6).abs() < 1e-15);
    }

    #[test]
    fn out_of_range_is_clamped_with_a_warning() {
        let (m, w) = parse_str("newmtl a\nKd 2 -1 0.5\nTr 1.5\n");
        let m = m.unwrap();
        assert_eq!(m[0].diffuse, [1.0, 0.0, 0.5]);
        assert_eq!(m[0].transparency, 1.0);
        assert_eq!(w.len(), 3);
        assert!(w[0].starts_with("t.mtl:2:"), "{w:?}");
    }

    #[test]
    fn errors_name_the_line() {
        for (src, line, needle) in [
            ("newmtl a\nKd 1 x 0\n", 2, "bad number"),
            ("newmtl a\n\nKd 1 0\n", 3, "1 or 3 values"),
            ("newmtl a\nd nan\n", 2, "not finite"),
            ("newmtl a\nTr 0.1 0.2\n", 2, "1 value"),
            ("newmtl\n", 1, "without a name"),
        ] {
            let e = parse_str(src).0.unwrap_err();
            assert_eq!(e.file, "t.mtl");
            assert_eq!(e.location, Location::Line(line), "{src:?}: {e}");
            assert!(e.message.contains(needle), "{src:?}: {e}");
        }
    }

    #[test]
    fn texture_options_are_skipped_and_the_rest_is_the_file() {
        let mut w = Vec::new();
        let src = "newmtl a\nmap_Kd -s 2 2 1 -clamp on tex.png\nnewmtl b\nmap_Kd -o 0.5 -mm 0 1 my tex.png\n\
                   newmtl c\nmap_Kd -t 1 -blendu off 2.png\nnewmtl d\n";
        let (_, t) = parse_with_textures(src.as_bytes(), "t.mtl", &mut w).unwrap();
        assert!(w.is_empty(), "{w:?}");
        let t: Vec<Option<&[u8]>> = t.iter().map(|t| t.as_deref()).collect();
        assert_eq!(
            t,
            [
                Some(&b"tex.png"[..]),
                Some(&b"my tex.png"[..]),
                Some(&b"2.png"[..]),
                None
            ]
        );
        for (src, line) in [
            ("newmtl a\nmap_Kd\n", 2),
            ("newmtl a\nmap_Kd   # comment\n", 2),
            ("newmtl a\nKd 1 1 1\nmap_Kd -s 1 1 1\n", 3),
            ("newmtl a\nmap_Kd -clamp\n", 2),
            ("newmtl a\nmap_Kd -mm 0 1\n", 2),
        ] {
            let e = parse_str(src).0.unwrap_err();
            assert_eq!(e.file, "t.mtl");
            assert_eq!(e.location, Location::Line(line), "{src:?}: {e}");
            assert!(e.message.contains("map_Kd without a file name"), "{e}");
        }
    }

    #[test]
    fn unknown_and_orphan_statements_warn() {
        let (m, w) = parse_str("Kd 1 1 1\nnewmtl a\nfoo 1\nfoo 2\nKd spectral x.rfl\n");
        assert_eq!(m.unwrap()[0].diffuse, [0.8; 3]);
        assert_eq!(w.len(), 3, "{w:?}");
    }
}
