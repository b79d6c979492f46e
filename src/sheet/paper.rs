//! What a sheet is drawn on and at: paper sizes, the drawing scale and its standard series,
//! model units, the projection method, the date, and the list of views, each parsed from the
//! command line's text with an error that names what is wrong.

use crate::camera::NamedView;
use std::fmt;

/// A paper size (ISO 216 A series, and the US Letter and Tabloid sizes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Paper {
    /// 297 x 210 mm.
    A4,
    /// 420 x 297 mm.
    A3,
    /// 594 x 420 mm.
    A2,
    /// 841 x 594 mm.
    A1,
    /// 1189 x 841 mm.
    A0,
    /// 11 x 8.5 in (279.4 x 215.9 mm).
    Letter,
    /// 17 x 11 in (431.8 x 279.4 mm).
    Tabloid,
}

impl Paper {
    /// The name written in the title block.
    pub fn name(self) -> &'static str {
        match self {
            Paper::A4 => "A4",
            Paper::A3 => "A3",
            Paper::A2 => "A2",
            Paper::A1 => "A1",
            Paper::A0 => "A0",
            Paper::Letter => "LETTER",
            Paper::Tabloid => "TABLOID",
        }
    }

    /// Width and height in mm, landscape (the longer side across).
    pub fn landscape_mm(self) -> (f64, f64) {
        match self {
            Paper::A4 => (297.0, 210.0),
            Paper::A3 => (420.0, 297.0),
            Paper::A2 => (594.0, 420.0),
            Paper::A1 => (841.0, 594.0),
            Paper::A0 => (1189.0, 841.0),
            Paper::Letter => (279.4, 215.9),
            Paper::Tabloid => (431.8, 279.4),
        }
    }
}

/// How the orthographic views are arranged around the front view (ISO 5456-2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ProjectionMethod {
    /// Each view is placed on the side it is seen from: the top view above the front view,
    /// the right view to its right (North America's usage).
    Third,
    /// Each view is placed opposite the side it is seen from: the top view below the front
    /// view, the right view to its left (Europe's and ISO's usual usage).
    First,
}

impl ProjectionMethod {
    /// The text in the title block.
    pub fn name(self) -> &'static str {
        match self {
            ProjectionMethod::Third => "THIRD ANGLE",
            ProjectionMethod::First => "FIRST ANGLE",
        }
    }
}

/// The unit of the model's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Units {
    /// Millimetres (the default: CAD exports in mm).
    Mm,
    /// Centimetres.
    Cm,
    /// Metres.
    M,
    /// Inches.
    In,
}

impl Units {
    /// Millimetres in one unit.
    pub fn mm(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Cm => 10.0,
            Units::M => 1000.0,
            Units::In => 25.4,
        }
    }
}

/// A drawing scale `paper:model` (`1:2`: one mm on paper for two of the model), one side 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scale {
    /// The paper side.
    pub paper: u32,
    /// The model side.
    pub model: u32,
}

/// The largest number either side of a scale may have.
const MAX_SCALE_SIDE: u32 = 1_000_000;

impl Scale {
    /// Full size.
    pub const FULL: Scale = Scale { paper: 1, model: 1 };

    /// Paper mm per model mm.
    pub fn factor(self) -> f64 {
        f64::from(self.paper) / f64::from(self.model)
    }

    /// The standard series of ISO 5455, continued by the same 1-2-5 steps: 1000:1, 500:1,
    /// 200:1, ..., 2:1, 1:1, 1:2, 1:5, 1:10, ..., 1:1000000, largest first.
    pub fn series() -> impl Iterator<Item = Scale> {
        // 1-2-5 steps per decade: 1000:1, 500:1, ..., 2:1, then 1:1, 1:2, ..., 1:1000000.
        let decade = |e: u32, steps: [u32; 3]| steps.map(move |m| m * 10u32.pow(e));
        let enlargements = std::iter::once(1000)
            .chain((0..3).rev().flat_map(move |e| decade(e, [5, 2, 1])))
            .filter(|&n| n > 1)
            .map(|paper| Scale { paper, model: 1 });
        let reductions = (0..6)
            .flat_map(move |e| decade(e, [1, 2, 5]))
            .chain(std::iter::once(MAX_SCALE_SIDE))
            .map(|model| Scale { paper: 1, model });
        enlargements.chain(reductions)
    }

    /// Is it in [`Scale::series`]?
    pub fn is_standard(self) -> bool {
        Scale::series().any(|s| s == self)
    }

    /// Parses `1:N` or `N:1` (N a whole number from 1 to 1,000,000). Scales outside the
    /// standard series (`1:3`, `1:25`) are accepted, as ISO 5455 allows in special cases; a
    /// scale with neither side 1 (`3:7`) is not a drawing scale and is refused.
    pub fn parse(s: &str) -> Result<Scale, String> {
        let bad = || {
            format!(
                "'{s}' is not a drawing scale: write 1:N or N:1 with N a whole number from 1 to {MAX_SCALE_SIDE} (1:2, 1:10, 2:1)"
            )
        };
        let (a, b) = s.trim().split_once(':').ok_or_else(bad)?;
        let side = |t: &str| {
            t.trim()
                .parse::<u32>()
                .ok()
                .filter(|v| (1..=MAX_SCALE_SIDE).contains(v))
        };
        match (side(a), side(b)) {
            (Some(paper), Some(model)) if paper == 1 || model == 1 => Ok(Scale { paper, model }),
            _ => Err(bad()),
        }
    }
}

impl fmt::Display for Scale {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.paper, self.model)
    }
}

/// A calendar date `YYYY-MM-DD` for the title block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SheetDate(String);

impl SheetDate {
    /// Parses `YYYY-MM-DD`, a real day of the Gregorian calendar.
    pub fn parse(s: &str) -> Result<SheetDate, String> {
        let bad = |why: &str| format!("'{s}' is not a date YYYY-MM-DD: {why}");
        let parts: Vec<&str> = s.split('-').collect();
        let [y, m, d] = parts[..] else {
            return Err(bad("expected three parts separated by '-'"));
        };
        let digits = |t: &str, n: usize| t.len() == n && t.bytes().all(|c| c.is_ascii_digit());
        if !(digits(y, 4) && digits(m, 2) && digits(d, 2)) {
            return Err(bad("expected 4, 2 and 2 digits"));
        }
        let (year, month, day): (u32, u32, u32) = (
            y.parse().map_err(|_| bad("year"))?,
            m.parse().map_err(|_| bad("month"))?,
            d.parse().map_err(|_| bad("day"))?,
        );
        let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
        let days = match month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if leap => 29,
            2 => 28,
            _ => return Err(bad(&format!("no month {month}"))),
        };
        if !(1..=days).contains(&day) {
            return Err(bad(&format!("month {month} of {year} has no day {day}")));
        }
        Ok(SheetDate(s.to_string()))
    }

    /// The date as given.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

/// Every view a sheet can show, by its name on the command line.
pub const VIEW_NAMES: [(&str, NamedView); 7] = [
    ("front", NamedView::Front),
    ("back", NamedView::Back),
    ("top", NamedView::Top),
    ("bottom", NamedView::Bottom),
    ("left", NamedView::Left),
    ("right", NamedView::Right),
    ("iso", NamedView::Iso),
];

/// The name of a view on the command line (`front`).
pub fn view_name(view: NamedView) -> &'static str {
    VIEW_NAMES
        .iter()
        .find(|(_, v)| *v == view)
        .map_or("?", |(n, _)| n)
}

/// Parses a comma-separated list of views (`front,top,right,iso`): each known, none twice.
pub fn parse_views(s: &str) -> Result<Vec<NamedView>, String> {
    let mut views = Vec::new();
    for name in s.split(',').map(str::trim) {
        let Some(&(_, view)) = VIEW_NAMES
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
        else {
            let known: Vec<&str> = VIEW_NAMES.iter().map(|(n, _)| *n).collect();
            return Err(format!(
                "unknown view '{name}' (the views are {})",
                known.join(", ")
            ));
        };
        if views.contains(&view) {
            return Err(format!("view '{name}' is given twice"));
        }
        views.push(view);
    }
    Ok(views)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_series_runs_one_two_five_largest_first() {
        let names: Vec<String> = Scale::series().map(|s| s.to_string()).collect();
        let at = |s: &str| names.iter().position(|n| n == s).unwrap();
        assert_eq!(names[0], "1000:1");
        assert_eq!(names.last().unwrap(), "1:1000000");
        for w in [
            ["5:1", "2:1", "1:1", "1:2", "1:5", "1:10"],
            ["1:10", "1:20", "1:50", "1:100", "1:200", "1:500"],
            ["50:1", "20:1", "10:1", "5:1", "2:1", "1:1"],
        ] {
            for pair in w.windows(2) {
                assert_eq!(at(pair[0]) + 1, at(pair[1]), "{pair:?} in {names:?}");
            }
        }
        let factors: Vec<f64> = Scale::series().map(Scale::factor).collect();
        assert!(factors.windows(2).all(|w| w[0] > w[1]), "{factors:?}");
    }

    #[test]
    fn scales_parse_with_one_side_one() {
        assert_eq!(Scale::parse("1:2"), Ok(Scale { paper: 1, model: 2 }));
        assert_eq!(Scale::parse(" 5:1 "), Ok(Scale { paper: 5, model: 1 }));
        assert!(Scale::parse("1:25").unwrap().factor() == 0.04);
        assert!(!Scale::parse("1:25").unwrap().is_standard());
        assert!(Scale::parse("1:20").unwrap().is_standard());
        for bad in ["3:7", "1:0", "0:1", "1/2", "half", "1:-2", "1:2:3", ""] {
            let e = Scale::parse(bad).unwrap_err();
            assert!(
                e.contains(&format!("'{bad}'")) && e.contains("1:N or N:1"),
                "{e}"
            );
        }
    }

    #[test]
    fn dates_are_real_days() {
        assert_eq!(
            SheetDate::parse("2024-02-29").unwrap().as_str(),
            "2024-02-29"
        );
        for (bad, why) in [
            ("2023-02-29", "no day 29"),
            ("2024-13-01", "no month 13"),
            ("2024-1-01", "digits"),
            ("24-01-01", "digits"),
            ("2024/01/01", "three parts"),
            ("1900-02-29", "no day 29"),
        ] {
            let e = SheetDate::parse(bad).unwrap_err();
            assert!(e.contains(bad) && e.contains(why), "{bad}: {e}");
        }
    }

    #[test]
    fn views_parse_and_name_the_unknown_one() {
        assert_eq!(
            parse_views("front,TOP, right,iso"),
            Ok(vec![
                NamedView::Front,
                NamedView::Top,
                NamedView::Right,
                NamedView::Iso
            ])
        );
        let e = parse_views("front,frnt").unwrap_err();
        assert!(
            e.contains("unknown view 'frnt'") && e.contains("bottom"),
            "{e}"
        );
        assert!(
            parse_views("top,top")
                .unwrap_err()
                .contains("'top' is given twice")
        );
        assert!(parse_views("").unwrap_err().contains("unknown view ''"));
    }
}
