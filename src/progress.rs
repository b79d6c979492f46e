//! Progress of the long stages, for a caller that shows it (the CLI's bars on a terminal).
//!
//! A stage reports through a [`Report`]: `report(stage, done, total)`, `stage` a short label
//! ("visible set"). Invariant of every stage's reports, which [`Ticker`] keeps: `done` never
//! decreases, `done <= total`, and the last report has `done == total`. A stage whose amount of
//! work grows as it runs (the BSP's splits) may raise `total` between reports.
//!
//! Reporting must not slow the hot loops: [`Ticker::tick`] is one comparison per item and calls
//! the report at most [`Ticker::STEPS`] + 2 times per stage of a fixed total, whatever its size
//! (a growing total adds about `STEPS` calls each time it doubles).

/// Where a stage's progress goes: `(stage, done, total)`. See the module docs for the order of
/// the calls. `Sync`: a stage done in parts on several threads reports from each of them
/// ([`crate::visibility::strips`]).
pub type Report<'a> = &'a (dyn Fn(&'static str, u64, u64) + Sync);

/// Throttled progress of one stage: counts items and calls the report now and then.
pub struct Ticker<'a> {
    report: Option<Report<'a>>,
    stage: &'static str,
    total: u64,
    /// The next `done` worth a report.
    next: u64,
    done: u64,
}

impl<'a> Ticker<'a> {
    /// Reports per stage, about.
    pub const STEPS: u64 = 256;

    /// Starts `stage` with `total` items (reports 0 of `total`). `None`: no reports, no cost.
    pub fn new(report: Option<Report<'a>>, stage: &'static str, total: u64) -> Self {
        if let Some(r) = report {
            r(stage, 0, total);
        }
        Ticker {
            report,
            stage,
            total,
            next: Self::step(total),
            done: 0,
        }
    }

    fn step(total: u64) -> u64 {
        total.div_ceil(Self::STEPS).max(1)
    }

    /// `done` items of the stage are complete (never fewer than at the last call).
    #[inline]
    pub fn tick(&mut self, done: u64) {
        if done >= self.next {
            self.send(done, self.total);
        }
    }

    /// As [`Self::tick`], for a stage whose total has grown to `total` (never less than
    /// before).
    #[inline]
    pub fn tick_of(&mut self, done: u64, total: u64) {
        self.total = self.total.max(total);
        if done >= self.next {
            self.send(done, total);
        }
    }

    #[cold]
    fn send(&mut self, done: u64, total: u64) {
        self.total = self.total.max(total);
        self.done = done.min(self.total);
        self.next = done + Self::step(self.total);
        if let Some(r) = self.report {
            r(self.stage, self.done, self.total);
        }
    }

    /// Ends the stage: reports `total` of `total`.
    pub fn finish(mut self) {
        self.done = self.total;
        if let Some(r) = self.report {
            r(self.stage, self.total, self.total);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn a_ticker_reports_a_few_monotone_steps_and_ends_at_the_total() {
        let calls = Mutex::new(Vec::new());
        let report = |s: &'static str, d: u64, t: u64| calls.lock().unwrap().push((s, d, t));
        let mut t = Ticker::new(Some(&report), "work", 100_000);
        for i in 0..=100_000 {
            t.tick(i);
        }
        t.finish();
        let calls = calls.into_inner().unwrap();
        assert!(calls.len() <= Ticker::STEPS as usize + 3, "{}", calls.len());
        assert_eq!(calls[0], ("work", 0, 100_000));
        assert_eq!(*calls.last().unwrap(), ("work", 100_000, 100_000));
        assert!(calls.windows(2).all(|w| w[0].1 <= w[1].1));
    }

    #[test]
    fn a_growing_total_is_reported_and_never_exceeded() {
        let calls = Mutex::new(Vec::new());
        let report = |_: &'static str, d: u64, t: u64| calls.lock().unwrap().push((d, t));
        let mut t = Ticker::new(Some(&report), "grow", 10);
        for i in 0..40 {
            t.tick_of(i, 10 + i);
        }
        t.finish();
        let calls = calls.into_inner().unwrap();
        assert!(calls.iter().all(|&(d, t)| d <= t));
        assert!(calls.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(*calls.last().unwrap(), (49, 49));
    }
}
