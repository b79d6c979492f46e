//! Plots of error against time, log-log, one figure per scene: one curve per measured method
//! (a point per size, labelled with the size), a vertical line at each exact object-space
//! method's time (its error is 0, which a log axis cannot show), and a ring on each image-space
//! method's point at the smallest size from which the exact method (`coverage`) is faster.
//!
//! Text needs a font: a TrueType sans-serif font of the system (DejaVu Sans, Liberation Sans,
//! ...) is registered once; without one, [`plot_scene`] fails with a message and the caller
//! goes on without plots.

use super::{Crossover, EXACT_REFERENCE, Row};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::sync::OnceLock;

/// Figure size in pixels (and SVG user units).
pub const FIGURE: (u32, u32) = (900, 620);

/// Fonts looked for, in order.
const FONT_PATHS: [&str; 6] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "/Library/Fonts/Arial.ttf",
];

/// Registers a system font as "sans-serif" (once); false when none is found.
pub fn font_available() -> bool {
    static FOUND: OnceLock<bool> = OnceLock::new();
    *FOUND.get_or_init(|| {
        for path in FONT_PATHS {
            if let Ok(bytes) = std::fs::read(path) {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                if plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                    return true;
                }
            }
        }
        false
    })
}

/// A method's colour: fixed per registry position, so a method has one colour in every figure.
fn colour(method: &str) -> RGBColor {
    const COLOURS: [RGBColor; 11] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(0, 0, 0),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    let k = crate::methods::METHODS
        .iter()
        .position(|m| m.name == method)
        .unwrap_or(0);
    COLOURS[k % COLOURS.len()]
}

/// The figure of `scene` as SVG text and as RGB pixels ([`FIGURE`] size, row-major).
pub fn plot_scene(
    scene: &str,
    rows: &[Row],
    crossovers: &[Crossover],
) -> Result<(String, Vec<[u8; 3]>), String> {
    if !font_available() {
        return Err("no TrueType font found for the plots' text (looked for DejaVu Sans, Liberation Sans, Arial)".into());
    }
    let rows: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
    let mut svg = String::new();
    draw(
        &SVGBackend::with_string(&mut svg, FIGURE).into_drawing_area(),
        scene,
        &rows,
        crossovers,
    )?;
    let (w, h) = FIGURE;
    let mut buf = vec![0u8; w as usize * h as usize * 3];
    draw(
        &BitMapBackend::with_buffer(&mut buf, FIGURE).into_drawing_area(),
        scene,
        &rows,
        crossovers,
    )?;
    let pixels = buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok((svg, pixels))
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scene: &str,
    rows: &[&Row],
    crossovers: &[Crossover],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let exact = |r: &Row| r.exact && r.engine == "object";
    let times: Vec<f64> = rows.iter().map(|r| r.time_s).filter(|t| *t > 0.0).collect();
    let errors: Vec<f64> = rows
        .iter()
        .filter(|r| !exact(r))
        .map(|r| r.error)
        .filter(|e| *e > 0.0)
        .collect();
    let range = |v: &[f64], default: (f64, f64)| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0, f64::max);
        if lo.is_finite() && hi > 0.0 {
            (lo / 2.0, hi * 2.0)
        } else {
            default
        }
    };
    let (t0, t1) = range(&times, (1e-4, 1.0));
    let (e0, e1) = range(&errors, (1e-4, 1.0));
    // Room below the lowest point for the legend (lower left).
    let e0 = e0 / (e1 / e0).powf(0.7);
    let mut chart = ChartBuilder::on(root)
        .caption(format!("{scene}: error against time"), ("sans-serif", 22))
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("time after projection (log)")
        .y_desc("error: fraction of image area on the wrong face (log)")
        .x_label_formatter(&time_label)
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let mut methods: Vec<&'static str> = Vec::new();
    for r in rows {
        if !methods.contains(&r.method) {
            methods.push(r.method);
        }
    }
    for m in methods {
        let c = colour(m);
        let mut runs: Vec<&Row> = rows.iter().copied().filter(|r| r.method == m).collect();
        runs.sort_by_key(|r| r.size);
        if runs.first().is_some_and(|r| exact(r)) {
            let t = runs[0].time_s;
            let label = if m == EXACT_REFERENCE {
                format!("{m}: exact, error 0 (vertical line at its time: log axes cannot show 0)")
            } else {
                format!("{m}: exact, error 0 (vertical line)")
            };
            chart
                .draw_series(LineSeries::new(
                    vec![(t, e0), (t, e1)],
                    c.stroke_width(if m == EXACT_REFERENCE { 3 } else { 1 }),
                ))
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y - 6), (x, y + 6)], c.stroke_width(3))
                });
            continue;
        }
        let points: Vec<(f64, f64, u32)> = runs
            .iter()
            .filter(|r| r.error > 0.0 && r.time_s > 0.0)
            .map(|r| (r.time_s, r.error, r.size))
            .collect();
        let cross = crossovers
            .iter()
            .find(|x| x.scene == rows[0].scene && x.method == m)
            .and_then(|x| x.from_size);
        let label = match cross {
            Some(s) => {
                format!("{m} (sizes as labelled; {EXACT_REFERENCE} faster from {s} px, ringed)")
            }
            None => format!("{m} (sizes as labelled)"),
        };
        // The painter's drawing happens after `render::compute`: only its sort is timed.
        let label = if m == "painter" {
            label.replace("(sizes", "(its depth sort only timed; sizes")
        } else {
            label
        };
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|&(t, er, _)| (t, er)),
                c.stroke_width(2),
            ))
            .map_err(e)?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(t, er, _)| Circle::new((t, er), 3, c.filled())),
            )
            .map_err(e)?;
        chart
            .draw_series(points.iter().map(|&(t, er, s)| {
                EmptyElement::at((t, er))
                    + Text::new(
                        format!("{s}"),
                        (6, -14),
                        ("sans-serif", 12).into_font().color(&c),
                    )
            }))
            .map_err(e)?;
        if let Some(s) = cross
            && let Some(&(t, er, _)) = points.iter().find(|p| p.2 == s)
        {
            chart
                .draw_series(std::iter::once(Circle::new((t, er), 9, c.stroke_width(2))))
                .map_err(e)?;
        }
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerLeft)
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// A time axis label in the unit that reads best ("20 ms", "1.5 s", "500 µs"), at 1, 2 and 5
/// times a power of ten only (plotters offers every integer multiple on a log axis, which
/// crowds the axis); empty elsewhere.
fn time_label(v: &f64) -> String {
    if !(v.is_finite() && *v > 0.0) {
        return String::new();
    }
    let decade = 10f64.powf(v.log10().floor());
    let mantissa = v / decade;
    let nearest = mantissa.round();
    if !matches!(nearest as i64, 1 | 2 | 5 | 10) || (mantissa - nearest).abs() > 0.01 * nearest {
        return String::new();
    }
    let round = |x: f64| {
        let s = format!("{:.3}", x);
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    if *v >= 1.0 {
        format!("{} s", round(*v))
    } else if *v >= 1e-3 {
        format!("{} ms", round(v * 1e3))
    } else {
        format!("{} µs", round(v * 1e6))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_labels_read_in_their_unit_at_one_two_and_five() {
        assert_eq!(time_label(&1.0), "1 s");
        assert_eq!(time_label(&0.02), "20 ms");
        assert_eq!(time_label(&5e-4), "500 µs");
        assert_eq!(time_label(&2.0), "2 s");
        assert_eq!(time_label(&10.0), "10 s");
        assert_eq!(time_label(&3.0), "");
        assert_eq!(time_label(&0.0), "");
    }
}
