//! Where the views go on a sheet: the orthographic views in their projection method's
//! arrangement at one scale, the pictorial view in the largest free area left.
//!
//! Invariants of a [`Layout`]:
//! - **Aligned**: the orthographic views sit on a grid of rows and columns around the front
//!   view's place (whether or not the front view is drawn): views in one column (front, top,
//!   bottom, back) have the same width and the same left edge, views in one row (front, left,
//!   right, back) the same height and the same top edge, all at the one scale. Third angle:
//!   top above the front view, bottom below, right to its right, left to its left; first
//!   angle: top below, bottom above, right to the left, left to the right; the back view is at
//!   the far right in both.
//! - **Inside**: every view, with its label below it, lies in the drawing area, at least
//!   [`GAP`] from every other view and from the title block.
//! - **Scale**: the one asked for, or the one of [`Scale::series`] at which the views fit that
//!   maximizes `min(scale, pictorial factor / ISO_MIN)` (the larger scale on ties): the largest
//!   that fits, unless the pictorial view would then get less than [`ISO_MIN`] of it and a
//!   smaller scale does better by both. The pictorial view is drawn at the sheet's scale when
//!   it fits there, else scaled down to fit (and labelled so), as near the orthographic views
//!   as its free area allows. With only the pictorial view, the largest scale at which it fits.
//! - Deterministic: candidates are tried in a fixed order and ties go to the first.

use super::paper::{ProjectionMethod, Scale};
use crate::camera::NamedView;

/// An axis-aligned rectangle on the sheet, mm, y down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Left.
    pub x0: f64,
    /// Top.
    pub y0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y1: f64,
}

impl Rect {
    /// The rectangle of this size with its top-left corner at `(x, y)`.
    pub fn at(x: f64, y: f64, w: f64, h: f64) -> Rect {
        Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        }
    }

    /// Width.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }

    /// Height.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }

    /// Its centre.
    pub fn centre(&self) -> [f64; 2] {
        [(self.x0 + self.x1) / 2.0, (self.y0 + self.y1) / 2.0]
    }

    /// Do the interiors meet?
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Is `o` inside (or on the edge of) this one?
    pub fn contains(&self, o: &Rect) -> bool {
        self.x0 <= o.x0 && o.x1 <= self.x1 && self.y0 <= o.y0 && o.y1 <= self.y1
    }

    /// Grown by `d` on every side.
    pub fn grown(&self, d: f64) -> Rect {
        Rect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, o: &Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }
}

/// The least space between two views, or a view and the title block, mm.
pub const GAP: f64 = 10.0;
/// The pictorial view's factor, as a fraction of the sheet's scale, below which a smaller
/// sheet scale is worth trying (see [`layout`]).
pub const ISO_MIN: f64 = 0.5;

/// An orthographic view's place around the front view: (row, column), row -1 above the front
/// view's row, column 1 right of its column.
pub fn cell(view: NamedView, method: ProjectionMethod) -> (i32, i32) {
    let third = method == ProjectionMethod::Third;
    let flip = if third { 1 } else { -1 };
    match view {
        NamedView::Front | NamedView::Iso => (0, 0),
        NamedView::Top => (-flip, 0),
        NamedView::Bottom => (flip, 0),
        NamedView::Right => (0, flip),
        NamedView::Left => (0, -flip),
        NamedView::Back => (0, 2),
    }
}

/// A view to place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Item {
    /// Which view.
    pub view: NamedView,
    /// Its frame's width and height, model mm.
    pub size: [f64; 2],
    /// Its label's width, and the height the label takes under the frame, mm.
    pub label: [f64; 2],
}

/// What to lay out.
#[derive(Clone, Debug)]
pub struct Request<'a> {
    /// The orthographic views.
    pub ortho: &'a [Item],
    /// The pictorial view, if there is one.
    pub iso: Option<Item>,
    /// The arrangement.
    pub method: ProjectionMethod,
    /// Where views may go, mm.
    pub area: Rect,
    /// What they must keep [`GAP`] away from (the title block).
    pub keep_out: Rect,
    /// The scale asked for, if any.
    pub scale: Option<Scale>,
}

/// Where the views go.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// The orthographic views' scale.
    pub scale: Scale,
    /// Each orthographic view's frame on the sheet, in the request's order.
    pub ortho: Vec<Rect>,
    /// The pictorial view's frame and its factor (paper mm per model mm).
    pub iso: Option<(Rect, f64)>,
}

impl Layout {
    /// Is the pictorial view at the sheet's scale?
    pub fn iso_to_scale(&self) -> bool {
        self.iso.is_some_and(|(_, f)| f == self.scale.factor())
    }
}

/// A frame with its label (`[width, height]`) centred under it.
pub fn with_label(frame: &Rect, label: [f64; 2]) -> Rect {
    let cx = (frame.x0 + frame.x1) / 2.0;
    Rect {
        x0: frame.x0.min(cx - label[0] / 2.0),
        y0: frame.y0,
        x1: frame.x1.max(cx + label[0] / 2.0),
        y1: frame.y1 + label[1],
    }
}

/// The orthographic views' frames at `factor` with the group's top-left at the origin, and
/// the group's size. A column is as wide as its widest frame or label, a row as high as its
/// highest frame and label; frames are centred in their column and at the top of their row,
/// so frames of one column (row) have the same left edge (top edge).
fn group(ortho: &[Item], method: ProjectionMethod, factor: f64) -> (Vec<Rect>, f64, f64) {
    let cells: Vec<(i32, i32)> = ortho.iter().map(|it| cell(it.view, method)).collect();
    let mut cols: Vec<i32> = cells.iter().map(|c| c.1).collect();
    let mut rows: Vec<i32> = cells.iter().map(|c| c.0).collect();
    cols.sort_unstable();
    cols.dedup();
    rows.sort_unstable();
    rows.dedup();
    let widest = |c: i32| {
        ortho
            .iter()
            .zip(&cells)
            .filter(|(_, k)| k.1 == c)
            .map(|(it, _)| (it.size[0] * factor).max(it.label[0]))
            .fold(0.0, f64::max)
    };
    let highest = |r: i32| {
        ortho
            .iter()
            .zip(&cells)
            .filter(|(_, k)| k.0 == r)
            .map(|(it, _)| it.size[1] * factor + it.label[1])
            .fold(0.0, f64::max)
    };
    let widths: Vec<f64> = cols.iter().map(|&c| widest(c)).collect();
    let heights: Vec<f64> = rows.iter().map(|&r| highest(r)).collect();
    let starts = |sizes: &[f64]| {
        let mut at = Vec::with_capacity(sizes.len());
        let mut x = 0.0;
        for s in sizes {
            at.push(x);
            x += s + GAP;
        }
        (at, (x - GAP).max(0.0))
    };
    let (col_x, width) = starts(&widths);
    let (row_y, height) = starts(&heights);
    let frames = ortho
        .iter()
        .zip(&cells)
        .map(|(it, (r, c))| {
            let ci = cols.binary_search(c).expect("a used column");
            let ri = rows.binary_search(r).expect("a used row");
            let w = it.size[0] * factor;
            Rect::at(
                col_x[ci] + (widths[ci] - w) / 2.0,
                row_y[ri],
                w,
                it.size[1] * factor,
            )
        })
        .collect();
    (frames, width, height)
}

/// The best free rectangle for `item` with its label, among rectangles of `area` whose
/// interiors meet none of `obstacles`: its factor (paper per model) and the rectangle.
/// Candidates are bounded by the obstacles' and the area's edges.
fn best_free(area: &Rect, obstacles: &[Rect], item: &Item) -> Option<(f64, Rect)> {
    let mut xs = vec![area.x0, area.x1];
    let mut ys = vec![area.y0, area.y1];
    for o in obstacles {
        xs.extend([o.x0, o.x1].map(|x| x.clamp(area.x0, area.x1)));
        ys.extend([o.y0, o.y1].map(|y| y.clamp(area.y0, area.y1)));
    }
    for v in [&mut xs, &mut ys] {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    let mut best: Option<(f64, Rect)> = None;
    for (i, &x0) in xs.iter().enumerate() {
        for &x1 in &xs[i + 1..] {
            if x1 - x0 < item.label[0] {
                continue;
            }
            for (k, &y0) in ys.iter().enumerate() {
                for &y1 in &ys[k + 1..] {
                    let r = Rect { x0, y0, x1, y1 };
                    let free_height = r.height() - item.label[1];
                    if free_height <= 0.0 || obstacles.iter().any(|o| o.overlaps(&r)) {
                        continue;
                    }
                    let f = (r.width() / item.size[0]).min(free_height / item.size[1]);
                    if best.is_none_or(|(b, _)| f > b) {
                        best = Some((f, r));
                    }
                }
            }
        }
    }
    best
}

/// The pictorial view's frame at factor `f` in the free rectangle `free`, as near `target` as
/// it goes (so that it keeps close to the orthographic views).
fn place_iso(item: &Item, f: f64, free: &Rect, target: [f64; 2]) -> Rect {
    let (w, h) = (item.size[0] * f, item.size[1] * f);
    let (cw, ch) = (w.max(item.label[0]), h + item.label[1]);
    let cx = target[0].clamp(
        free.x0 + cw / 2.0,
        (free.x1 - cw / 2.0).max(free.x0 + cw / 2.0),
    );
    let cy = target[1].clamp(
        free.y0 + ch / 2.0,
        (free.y1 - ch / 2.0).max(free.y0 + ch / 2.0),
    );
    Rect::at(cx - w / 2.0, cy - ch / 2.0, w, h)
}

/// One arrangement at one scale: the orthographic frames, the pictorial frame and factor, and
/// its score (larger is better).
struct Candidate {
    ortho: Vec<Rect>,
    iso: Option<(Rect, f64)>,
    score: (f64, f64),
}

/// The best arrangement at `factor`, `None` when the views do not fit. The pictorial view is
/// at most at `factor`; arrangements are compared by its factor, then by how near the middle
/// of the area the views' extent is centred.
fn arrange(req: &Request, factor: f64) -> Option<Candidate> {
    let (frames, w, h) = group(req.ortho, req.method, factor);
    let a = &req.area;
    let keep_out = req.keep_out.grown(GAP);
    let xs = [a.x0, (a.x0 + a.x1 - w) / 2.0, a.x1 - w, keep_out.x0 - w];
    let ys = [a.y0, (a.y0 + a.y1 - h) / 2.0, a.y1 - h, keep_out.y0 - h];
    let mut best: Option<Candidate> = None;
    for &gy in &ys {
        for &gx in &xs {
            let placed: Vec<Rect> = frames
                .iter()
                .map(|r| Rect::at(r.x0 + gx, r.y0 + gy, r.width(), r.height()))
                .collect();
            let cells: Vec<Rect> = placed
                .iter()
                .zip(req.ortho)
                .map(|(r, it)| with_label(r, it.label))
                .collect();
            if !cells
                .iter()
                .all(|c| a.contains(c) && !c.overlaps(&keep_out))
            {
                continue;
            }
            let group_box = cells.iter().copied().reduce(|u, r| u.union(&r));
            let mut obstacles: Vec<Rect> = cells.iter().map(|c| c.grown(GAP)).collect();
            obstacles.push(keep_out);
            let iso = match &req.iso {
                None => None,
                Some(item) => {
                    let Some((f, free)) = best_free(a, &obstacles, item) else {
                        continue;
                    };
                    let f = f.min(factor);
                    let target = group_box.map_or(a.centre(), |g| g.centre());
                    Some((place_iso(item, f, &free, target), f))
                }
            };
            let iso_cell = iso
                .as_ref()
                .zip(req.iso.as_ref())
                .map(|((r, _), it)| with_label(r, it.label));
            let Some(all) = group_box
                .into_iter()
                .chain(iso_cell)
                .reduce(|u, r| u.union(&r))
            else {
                continue;
            };
            let ([cx, cy], [ax, ay]) = (all.centre(), a.centre());
            let balance = -((cx - ax).powi(2) + (cy - ay).powi(2)).sqrt();
            let score = (iso.map_or(0.0, |(_, f)| f), balance);
            if best.as_ref().is_none_or(|b| score > b.score) {
                best = Some(Candidate {
                    ortho: placed,
                    iso,
                    score,
                });
            }
        }
    }
    best
}

/// How good a scale is, given the arrangement it allows: the scale itself, but no more than
/// the pictorial view's factor over [`ISO_MIN`]; with only a pictorial view, the scale when
/// that view fits at it, else nothing.
fn worth(req: &Request, c: &Candidate, factor: f64) -> f64 {
    match (req.ortho.is_empty(), c.iso) {
        (_, None) => factor,
        (true, Some((_, f))) => {
            if f >= factor {
                factor
            } else {
                0.0
            }
        }
        (false, Some((_, f))) => factor.min(f / ISO_MIN),
    }
}

/// Lays out the views: see the module's invariants. The error says what does not fit.
pub fn layout(req: &Request) -> Result<Layout, String> {
    if req.ortho.is_empty() && req.iso.is_none() {
        return Err("no view to draw".into());
    }
    let done = |scale: Scale, c: Candidate| Layout {
        scale,
        ortho: c.ortho,
        iso: c.iso,
    };
    if let Some(scale) = req.scale {
        let factor = scale.factor();
        return match arrange(req, factor) {
            Some(c) if worth(req, &c, factor) > 0.0 => Ok(done(scale, c)),
            _ => Err(format!(
                "the views do not fit at {scale}{}",
                largest_fitting(req)
            )),
        };
    }
    // The standard scale worth most, the larger on ties; a scale is worth at most itself, so
    // the search stops below the best worth found.
    let mut best: Option<(f64, Scale, Candidate)> = None;
    for scale in Scale::series() {
        let factor = scale.factor();
        if best.as_ref().is_some_and(|(w, _, _)| factor < *w) {
            break;
        }
        let Some(c) = arrange(req, factor) else {
            continue;
        };
        let w = worth(req, &c, factor);
        if w > 0.0 && best.as_ref().is_none_or(|(b, _, _)| w > *b) {
            best = Some((w, scale, c));
        }
    }
    best.map(|(_, s, c)| done(s, c))
        .ok_or_else(|| "the views do not fit at any scale".into())
}

/// `"; the largest standard scale that fits is 1:5"`, or nothing when none does.
fn largest_fitting(req: &Request) -> String {
    let auto = Request {
        scale: None,
        ..req.clone()
    };
    match layout(&auto) {
        Ok(l) => format!("; the scale chosen without --scale would be {}", l.scale),
        Err(_) => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An A3 landscape sheet's drawing area and title block (as the sheet module makes them).
    fn a3() -> (Rect, Rect) {
        (
            Rect {
                x0: 25.0,
                y0: 15.0,
                x1: 405.0,
                y1: 282.0,
            },
            Rect::at(230.0, 259.0, 180.0, 28.0),
        )
    }

    const LABEL: [f64; 2] = [12.0, 8.0];

    fn item(view: NamedView, size: [f64; 2]) -> Item {
        Item {
            view,
            size,
            label: LABEL,
        }
    }

    fn request(ortho: &[Item], iso: Option<[f64; 2]>, method: ProjectionMethod) -> Request<'_> {
        let (area, keep_out) = a3();
        Request {
            ortho,
            iso: iso.map(|size| item(NamedView::Iso, size)),
            method,
            area,
            keep_out,
            scale: None,
        }
    }

    fn box_views(x: f64, y: f64, z: f64) -> Vec<Item> {
        vec![
            item(NamedView::Front, [x, y]),
            item(NamedView::Top, [x, z]),
            item(NamedView::Right, [z, y]),
        ]
    }

    /// The scale is the largest of the series that fits: a 100 mm cube's three views need
    /// 210 x 226 mm with gaps and labels and fit A3 at 1:1; at 2:1 they would need 410 mm
    /// across and do not.
    #[test]
    fn the_scale_is_the_largest_of_the_series_that_fits() {
        let views = box_views(100.0, 100.0, 100.0);
        let l = layout(&request(&views, None, ProjectionMethod::Third)).unwrap();
        assert_eq!(l.scale, Scale::FULL);
        // Too big for 1:1 (a 200 mm cube) goes to 1:2, not to some 1:1.3.
        let views = box_views(200.0, 200.0, 200.0);
        let l = layout(&request(&views, None, ProjectionMethod::Third)).unwrap();
        assert_eq!(l.scale, Scale { paper: 1, model: 2 });
        // Small parts are enlarged: a 10 mm cube at 10:1.
        let views = box_views(10.0, 10.0, 10.0);
        let l = layout(&request(&views, None, ProjectionMethod::Third)).unwrap();
        assert_eq!(
            l.scale,
            Scale {
                paper: 10,
                model: 1
            }
        );
        // Whatever the chosen scale, the next larger one of the series does not fit.
        for size in [3.0, 37.0, 140.0, 999.0, 12345.0] {
            let views = box_views(size, size * 0.6, size * 0.3);
            let req = request(&views, None, ProjectionMethod::First);
            let l = layout(&req).unwrap();
            let larger = Scale::series()
                .take_while(|s| *s != l.scale)
                .last()
                .unwrap();
            let at = Request {
                scale: Some(larger),
                ..req
            };
            assert!(
                layout(&at).is_err(),
                "{size}: {} chosen, {larger} fits",
                l.scale
            );
        }
    }

    /// A wide front view fits A3 at 1:1 with little room left for the pictorial view. A
    /// pictorial view that still gets more than half of what 1:2 would give it keeps 1:1 (not
    /// to scale); one that would get less than half makes the sheet 1:2.
    #[test]
    fn the_scale_gives_way_to_the_pictorial_view_only_when_that_pays() {
        let views = vec![item(NamedView::Front, [360.0, 150.0])];
        let l = layout(&request(
            &views,
            Some([300.0, 300.0]),
            ProjectionMethod::Third,
        ))
        .unwrap();
        assert_eq!(l.scale, Scale::FULL);
        assert!(!l.iso_to_scale());
        let l = layout(&request(
            &views,
            Some([600.0, 600.0]),
            ProjectionMethod::Third,
        ))
        .unwrap();
        assert_eq!(l.scale, Scale { paper: 1, model: 2 });
        // Without the pictorial view: the largest that fits.
        assert_eq!(
            layout(&request(&views, None, ProjectionMethod::Third))
                .unwrap()
                .scale,
            Scale::FULL
        );
    }

    /// A pictorial view alone is drawn at the largest standard scale at which it fits.
    #[test]
    fn a_lone_pictorial_view_is_to_scale() {
        let l = layout(&request(&[], Some([300.0, 150.0]), ProjectionMethod::Third)).unwrap();
        assert_eq!(l.scale, Scale::FULL);
        assert!(l.iso_to_scale());
        let l = layout(&request(&[], Some([30.0, 15.0]), ProjectionMethod::Third)).unwrap();
        assert_eq!(
            l.scale,
            Scale {
                paper: 10,
                model: 1
            }
        );
    }

    #[test]
    fn a_scale_asked_for_is_kept_or_refused_with_the_one_that_fits() {
        let views = box_views(200.0, 200.0, 200.0);
        let mut req = request(&views, None, ProjectionMethod::Third);
        req.scale = Some(Scale { paper: 1, model: 3 });
        assert_eq!(layout(&req).unwrap().scale, Scale { paper: 1, model: 3 });
        req.scale = Some(Scale::FULL);
        let e = layout(&req).unwrap_err();
        assert!(
            e.contains("do not fit at 1:1") && e.contains("without --scale would be 1:2"),
            "{e}"
        );
    }

    /// Third angle: top above front, right to its right; first angle: top below, right to the
    /// left. Front and top share their column's left edge, front and right their row's top.
    #[test]
    fn views_follow_the_projection_method() {
        let views = box_views(80.0, 50.0, 30.0);
        for method in [ProjectionMethod::Third, ProjectionMethod::First] {
            let l = layout(&request(&views, None, method)).unwrap();
            let [front, top, right] = [l.ortho[0], l.ortho[1], l.ortho[2]];
            assert_eq!(front.x0, top.x0);
            assert_eq!(front.x1, top.x1);
            assert_eq!(front.y0, right.y0);
            assert_eq!(front.y1, right.y1);
            match method {
                ProjectionMethod::Third => {
                    assert!(top.y1 < front.y0, "top above front");
                    assert!(right.x0 > front.x1, "right right of front");
                }
                ProjectionMethod::First => {
                    assert!(top.y0 > front.y1, "top below front");
                    assert!(right.x1 < front.x0, "right left of front");
                }
            }
        }
    }

    #[test]
    fn all_six_views_keep_their_places() {
        let views = vec![
            item(NamedView::Front, [4.0, 3.0]),
            item(NamedView::Back, [4.0, 3.0]),
            item(NamedView::Top, [4.0, 2.0]),
            item(NamedView::Bottom, [4.0, 2.0]),
            item(NamedView::Left, [2.0, 3.0]),
            item(NamedView::Right, [2.0, 3.0]),
        ];
        for method in [ProjectionMethod::Third, ProjectionMethod::First] {
            let l = layout(&request(&views, None, method)).unwrap();
            let r = |i: usize| l.ortho[i];
            let (front, back, top, bottom, left, right) = (r(0), r(1), r(2), r(3), r(4), r(5));
            let third = method == ProjectionMethod::Third;
            assert_eq!(top.y1 < front.y0, third);
            assert_eq!(bottom.y0 > front.y1, third);
            assert_eq!(right.x0 > front.x1, third);
            assert_eq!(left.x1 < front.x0, third);
            assert!(back.x0 > left.x1.max(right.x1), "back at the far right");
            for v in [back, left, right] {
                assert_eq!((v.y0, v.y1), (front.y0, front.y1));
            }
            for v in [top, bottom] {
                assert_eq!((v.x0, v.x1), (front.x0, front.x1));
            }
        }
    }

    /// Every view and the pictorial one lie in the area, apart from each other and from the
    /// title block.
    #[test]
    fn views_keep_apart_and_off_the_title_block() {
        let (area, keep_out) = a3();
        for (x, y, z) in [(100.0, 60.0, 40.0), (300.0, 20.0, 20.0), (10.0, 80.0, 5.0)] {
            let views = box_views(x, y, z);
            let iso = [0.8 * (x + z), 0.5 * (x + z) + 0.8 * y];
            let l = layout(&request(&views, Some(iso), ProjectionMethod::Third)).unwrap();
            let mut cells: Vec<Rect> = l.ortho.iter().map(|r| with_label(r, LABEL)).collect();
            let (iso_rect, f) = l.iso.unwrap();
            assert!(f <= l.scale.factor());
            cells.push(with_label(&iso_rect, LABEL));
            for (i, c) in cells.iter().enumerate() {
                assert!(area.contains(c), "{c:?}");
                assert!(!c.overlaps(&keep_out.grown(GAP - 1e-9)));
                for d in &cells[i + 1..] {
                    assert!(
                        !c.grown(GAP / 2.0 - 1e-9)
                            .overlaps(&d.grown(GAP / 2.0 - 1e-9))
                    );
                }
            }
        }
    }
}
