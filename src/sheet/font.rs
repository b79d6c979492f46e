//! Text drawn as strokes in a single-stroke font, so a sheet needs no font to display or to
//! convert to PDF: every letter is a few polylines.
//!
//! The font is Hershey's Roman Simplex (glyphs 699-2273 of the Hershey set, as the `rowmans`
//! font of the Hershey distributions; the table below is that font's data for ASCII 32-126 and
//! the degree sign, taken from the `Hershey-Fonts` package's `rowmans`). No maintained Rust crate
//! ships the data (the `hershey` crate on crates.io parses the format and holds no font), and
//! the table is small.
//!
//! The Hershey fonts were made by Dr. A. V. Hershey at the U.S. National Bureau of Standards;
//! as distributed by the U.S. NTIS, with the usual notice: "This distribution of the Hershey
//! Fonts may be used by anyone for any purpose, commercial or otherwise, providing that: 1. The
//! following acknowledgements must be distributed with the font data: - The Hershey Fonts were
//! originally created by Dr. A. V. Hershey while working at the U. S. National Bureau of
//! Standards. - The format of the Font data in this distribution was originally created by
//! James Hurt, Cognition, Inc., 900 Technology Park Drive, Billerica, MA 01821, (mit-eddie!
//! ci-dandelion!hurt) 2. The font data in this distribution may be converted into any other
//! format *EXCEPT* the format distributed by the U.S. NTIS (which organization holds the rights
//! to the distribution and use of the font data in that particular format)."
//!
//! Invariants: [`text_paths`] draws only from the table (a character outside it is drawn as
//! `?`); its output depends only on its arguments.

/// Each glyph in Hershey's encoding: pairs of characters, each coordinate its offset from `R`;
/// the first pair is the glyph's left and right bearing, then the points, ` R` lifting the
/// pen. y grows downward; capitals span y = -12 (cap line) to 9 (baseline).
const GLYPHS: [&str; 96] = [
    r#"JZ"#,                                                                     // ' ' (699)
    r#"MWRFRT RRYQZR[SZRY"#,                                                     // '!' (714)
    r#"JZNFNM RVFVM"#,                                                           // '"' (717)
    r#"H]SBLb RYBRb RLOZO RKUYU"#,                                               // '#' (733)
    r#"H\PBP_ RTBT_ RYIWGTFPFMGKIKKLMMNOOUQWRXSYUYXWZT[P[MZKX"#,                 // '$' (719)
    r#"F^[FI[ RNFPHPJOLMMKMIKIIJGLFNFPGSHVHYG[F RWTUUTWTYV[X[ZZ[X[VYTWT"#,       // '%' (2271)
    r#"E_\O\N[MZMYNXPVUTXRZP[L[JZIYHWHUISJRQNRMSKSIRGPFNGMIMKNNPQUXWZY[[[\Z\Y"#, // '&' (734)
    r#"MWRHQGRFSGSIRKQL"#,                                                       // "'" (731)
    r#"KYVBTDRGPKOPOTPYR]T`Vb"#,                                                 // '(' (721)
    r#"KYNBPDRGTKUPUTTYR]P`Nb"#,                                                 // ')' (722)
    r#"JZRFRR RMIWO RWIMO"#,                                                     // '*' (2219)
    r#"E_RIR[ RIR[R"#,                                                           // '+' (725)
    r#"MWSZR[QZRYSZS\R^Q_"#,                                                     // ',' (711)
    r#"E_IR[R"#,                                                                 // '-' (724)
    r#"MWRYQZR[SZRY"#,                                                           // '.' (710)
    r#"G][BIb"#,                                                                 // '/' (720)
    r#"H\QFNGLJKOKRLWNZQ[S[VZXWYRYOXJVGSFQF"#,                                   // '0' (700)
    r#"H\NJPISFS["#,                                                             // '1' (701)
    r#"H\LKLJMHNGPFTFVGWHXJXLWNUQK[Y["#,                                         // '2' (702)
    r#"H\MFXFRNUNWOXPYSYUXXVZS[P[MZLYKW"#,                                       // '3' (703)
    r#"H\UFKTZT RUFU["#,                                                         // '4' (704)
    r#"H\WFMFLOMNPMSMVNXPYSYUXXVZS[P[MZLYKW"#,                                   // '5' (705)
    r#"H\XIWGTFRFOGMJLOLTMXOZR[S[VZXXYUYTXQVOSNRNOOMQLT"#,                       // '6' (706)
    r#"H\YFO[ RKFYF"#,                                                           // '7' (707)
    r#"H\PFMGLILKMMONSOVPXRYTYWXYWZT[P[MZLYKWKTLRNPQOUNWMXKXIWGTFPF"#,           // '8' (708)
    r#"H\XMWPURRSQSNRLPKMKLLINGQFRFUGWIXMXRWWUZR[P[MZLX"#,                       // '9' (709)
    r#"MWRMQNROSNRM RRYQZR[SZRY"#,                                               // ':' (712)
    r#"MWRMQNROSNRM RSZR[QZRYSZS\R^Q_"#,                                         // ';' (713)
    r#"F^ZIJRZ["#,                                                               // '<' (2241)
    r#"E_IO[O RIU[U"#,                                                           // '=' (726)
    r#"F^JIZRJ["#,                                                               // '>' (2242)
    r#"I[LKLJMHNGPFTFVGWHXJXLWNVORQRT RRYQZR[SZRY"#,                             // '?' (715)
    r#"E`WNVLTKQKOLNMMPMSNUPVSVUUVS RQKOMNPNSOUPV RWKVSVUXVZV\T]Q]O\L[JYHWGTFQFNGLHJJILHOHRIUJWLYNZQ[T[WZYYZX RXKWSWUXV"#, // '@' (2273)
    r#"I[RFJ[ RRFZ[ RMTWT"#,                                 // 'A' (501)
    r#"G\KFK[ RKFTFWGXHYJYLXNWOTP RKPTPWQXRYTYWXYWZT[K["#,   // 'B' (502)
    r#"H]ZKYIWGUFQFOGMILKKNKSLVMXOZQ[U[WZYXZV"#,             // 'C' (503)
    r#"G\KFK[ RKFRFUGWIXKYNYSXVWXUZR[K["#,                   // 'D' (504)
    r#"H[LFL[ RLFYF RLPTP RL[Y["#,                           // 'E' (505)
    r#"HZLFL[ RLFYF RLPTP"#,                                 // 'F' (506)
    r#"H]ZKYIWGUFQFOGMILKKNKSLVMXOZQ[U[WZYXZVZS RUSZS"#,     // 'G' (507)
    r#"G]KFK[ RYFY[ RKPYP"#,                                 // 'H' (508)
    r#"NVRFR["#,                                             // 'I' (509)
    r#"JZVFVVUYTZR[P[NZMYLVLT"#,                             // 'J' (510)
    r#"G\KFK[ RYFKT RPOY["#,                                 // 'K' (511)
    r#"HYLFL[ RL[X["#,                                       // 'L' (512)
    r#"F^JFJ[ RJFR[ RZFR[ RZFZ["#,                           // 'M' (513)
    r#"G]KFK[ RKFY[ RYFY["#,                                 // 'N' (514)
    r#"G]PFNGLIKKJNJSKVLXNZP[T[VZXXYVZSZNYKXIVGTFPF"#,       // 'O' (515)
    r#"G\KFK[ RKFTFWGXHYJYMXOWPTQKQ"#,                       // 'P' (516)
    r#"G]PFNGLIKKJNJSKVLXNZP[T[VZXXYVZSZNYKXIVGTFPF RSWY]"#, // 'Q' (517)
    r#"G\KFK[ RKFTFWGXHYJYLXNWOTPKP RRPY["#,                 // 'R' (518)
    r#"H\YIWGTFPFMGKIKKLMMNOOUQWRXSYUYXWZT[P[MZKX"#,         // 'S' (519)
    r#"JZRFR[ RKFYF"#,                                       // 'T' (520)
    r#"G]KFKULXNZQ[S[VZXXYUYF"#,                             // 'U' (521)
    r#"I[JFR[ RZFR["#,                                       // 'V' (522)
    r#"F^HFM[ RRFM[ RRFW[ R\FW["#,                           // 'W' (523)
    r#"H\KFY[ RYFK["#,                                       // 'X' (524)
    r#"I[JFRPR[ RZFRP"#,                                     // 'Y' (525)
    r#"H\YFK[ RKFYF RK[Y["#,                                 // 'Z' (526)
    r#"KYOBOb RPBPb ROBVB RObVb"#,                           // '[' (2223)
    r#"KYKFY^"#,                                             // backslash (804)
    r#"KYTBTb RUBUb RNBUB RNbUb"#,                           // ']' (2224)
    r#"JZPLRITL RMORJWO RRJR["#,                             // '^' (2262)
    r#"JZJ]Z]"#,                                             // '_' (999)
    r#"MWSFRGQIQKRLSKRJ"#,                                   // '`' (730)
    r#"I\XMX[ RXPVNTMQMONMPLSLUMXOZQ[T[VZXX"#,               // 'a' (601)
    r#"H[LFL[ RLPNNPMSMUNWPXSXUWXUZS[P[NZLX"#,               // 'b' (602)
    r#"I[XPVNTMQMONMPLSLUMXOZQ[T[VZXX"#,                     // 'c' (603)
    r#"I\XFX[ RXPVNTMQMONMPLSLUMXOZQ[T[VZXX"#,               // 'd' (604)
    r#"I[LSXSXQWOVNTMQMONMPLSLUMXOZQ[T[VZXX"#,               // 'e' (605)
    r#"MYWFUFSGRJR[ ROMVM"#,                                 // 'f' (606)
    r#"I\XMX]W`VaTbQbOa RXPVNTMQMONMPLSLUMXOZQ[T[VZXX"#,     // 'g' (607)
    r#"I\MFM[ RMQPNRMUMWNXQX["#,                             // 'h' (608)
    r#"NVQFRGSFREQF RRMR["#,                                 // 'i' (609)
    r#"MWRFSGTFSERF RSMS^RaPbNb"#,                           // 'j' (610)
    r#"IZMFM[ RWMMW RQSX["#,                                 // 'k' (611)
    r#"NVRFR["#,                                             // 'l' (612)
    r#"CaGMG[ RGQJNLMOMQNRQR[ RRQUNWMZM\N]Q]["#,             // 'm' (613)
    r#"I\MMM[ RMQPNRMUMWNXQX["#,                             // 'n' (614)
    r#"I\QMONMPLSLUMXOZQ[T[VZXXYUYSXPVNTMQM"#,               // 'o' (615)
    r#"H[LMLb RLPNNPMSMUNWPXSXUWXUZS[P[NZLX"#,               // 'p' (616)
    r#"I\XMXb RXPVNTMQMONMPLSLUMXOZQ[T[VZXX"#,               // 'q' (617)
    r#"KXOMO[ ROSPPRNTMWM"#,                                 // 'r' (618)
    r#"J[XPWNTMQMNNMPNRPSUTWUXWXXWZT[Q[NZMX"#,               // 's' (619)
    r#"MYRFRWSZU[W[ ROMVM"#,                                 // 't' (620)
    r#"I\MMMWNZP[S[UZXW RXMX["#,                             // 'u' (621)
    r#"JZLMR[ RXMR["#,                                       // 'v' (622)
    r#"G]JMN[ RRMN[ RRMV[ RZMV["#,                           // 'w' (623)
    r#"J[MMX[ RXMM["#,                                       // 'x' (624)
    r#"JZLMR[ RXMR[P_NaLbKb"#,                               // 'y' (625)
    r#"J[XMM[ RMMXM RM[X["#,                                 // 'z' (626)
    r#"KYTBRCQDPFPHQJRKSMSOQQ RRCQEQGRISJTLTNSPORSTTVTXSZR[Q]Q_Ra RQSSUSWRYQZP\P^Q`RaTb"#, // '{' (2225)
    r#"NVRBRb"#, // '|' (723)
    r#"KYPBRCSDTFTHSJRKQMQOSQ RRCSESGRIQJPLPNQPURQTPVPXQZR[S]S_Ra RSSQUQWRYSZT\T^S`RaPb"#, // '}' (2226)
    r#"F^IUISJPLONOPPTSVTXTZS[Q RISJQLPNPPQTTVUXUZT[Q[O"#, // '~' (2246)
    r#"KYQFOGNINKOMQNSNUMVKVIUGSFQF"#,                     // '°' (718)
];

/// Cap line to baseline in font units.
const CAP_HEIGHT: f64 = 21.0;
/// The baseline's y in font units.
const BASELINE: f64 = 9.0;

/// Where a text sits relative to its anchor point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// The anchor is the start of the baseline.
    Start,
    /// The anchor is the middle of the baseline.
    Middle,
    /// The anchor is the end of the baseline.
    End,
}

/// A glyph's data, `?` for characters the table lacks.
fn glyph(c: char) -> &'static str {
    let i = match c {
        ' '..='~' => c as usize - 32,
        '°' => 95,
        _ => '?' as usize - 32,
    };
    GLYPHS[i]
}

/// Font units of a coordinate character.
fn unit(c: u8) -> f64 {
    f64::from(c) - f64::from(b'R')
}

/// The advance width of `text` at cap height `height` (same units as `height`).
pub fn text_width(text: &str, height: f64) -> f64 {
    let scale = height / CAP_HEIGHT;
    text.chars()
        .map(|c| {
            let g = glyph(c).as_bytes();
            (unit(g[1]) - unit(g[0])) * scale
        })
        .sum()
}

/// The polylines of `text` with capitals `height` high, its baseline through `(x, y)` placed by
/// `anchor` (y grows downward, as in SVG).
pub fn text_polylines(
    text: &str,
    x: f64,
    y: f64,
    height: f64,
    anchor: Anchor,
) -> Vec<Vec<[f64; 2]>> {
    let scale = height / CAP_HEIGHT;
    let width = text_width(text, height);
    let mut pen_x = match anchor {
        Anchor::Start => x,
        Anchor::Middle => x - width / 2.0,
        Anchor::End => x - width,
    };
    let mut lines = Vec::new();
    for c in text.chars() {
        let g = glyph(c).as_bytes();
        let (left, right) = (unit(g[0]), unit(g[1]));
        let mut line: Vec<[f64; 2]> = Vec::new();
        for pair in g[2..].chunks_exact(2) {
            if pair == b" R" {
                if line.len() > 1 {
                    lines.push(std::mem::take(&mut line));
                }
                line.clear();
                continue;
            }
            let gx = (unit(pair[0]) - left) * scale;
            let gy = (unit(pair[1]) - BASELINE) * scale;
            line.push([pen_x + gx, y + gy]);
        }
        if line.len() > 1 {
            lines.push(line);
        }
        pen_x += (right - left) * scale;
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_is_well_formed() {
        for (i, g) in GLYPHS.iter().enumerate() {
            let b = g.as_bytes();
            assert!(b.len() >= 2 && b.len() % 2 == 0, "glyph {i}");
            assert!(unit(b[1]) > unit(b[0]), "glyph {i} has no width");
            for pair in b[2..].chunks_exact(2) {
                assert!(
                    pair == b" R" || pair.iter().all(|c| (b'!'..=b'~').contains(c)),
                    "glyph {i}"
                );
            }
        }
    }

    /// Capitals stand on the baseline and reach the cap height; the width adds up the
    /// advances; anchors shift the text by its width.
    #[test]
    fn capitals_span_the_cap_height_and_anchors_shift() {
        let lines = text_polylines("E", 10.0, 50.0, 7.0, Anchor::Start);
        let ys: Vec<f64> = lines.iter().flatten().map(|p| p[1]).collect();
        let (lo, hi) = ys
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
        assert!(
            (lo - 43.0).abs() < 1e-12 && (hi - 50.0).abs() < 1e-12,
            "{lo} {hi}"
        );
        let w = text_width("AB", 3.5);
        assert!((w - (text_width("A", 3.5) + text_width("B", 3.5))).abs() < 1e-12);
        let start = text_polylines("AB", 0.0, 0.0, 3.5, Anchor::Start);
        let end = text_polylines("AB", w, 0.0, 3.5, Anchor::End);
        let mid = text_polylines("AB", w / 2.0, 0.0, 3.5, Anchor::Middle);
        for (a, b) in start.iter().flatten().zip(end.iter().flatten()) {
            assert!((a[0] - b[0]).abs() < 1e-12);
        }
        for (a, b) in start.iter().flatten().zip(mid.iter().flatten()) {
            assert!((a[0] - b[0]).abs() < 1e-12);
        }
    }

    /// A space draws nothing; a character outside the table draws as `?`.
    #[test]
    fn unknown_characters_draw_as_a_question_mark() {
        assert!(text_polylines(" ", 0.0, 0.0, 3.5, Anchor::Start).is_empty());
        assert_eq!(
            text_polylines("é", 0.0, 0.0, 3.5, Anchor::Start),
            text_polylines("?", 0.0, 0.0, 3.5, Anchor::Start)
        );
    }
}
