//! The invariants of the exact [`VisibleSet`] as properties over random scenes, checked exactly
//! and independently of the library's predicates; with the named regressions the properties
//! found. One test binary, four modules:
//!
//! - [`generators`]: random scenes and cameras, each following from a `Case { kind, n, seed }`;
//! - [`oracle`]: exact geometry in big integers and rationals, sharing no predicate with the
//!   kernel: piece vertices solved from their two lines' integer coefficients as homogeneous
//!   points (`Line::Cut(p, q)` has coefficients `c_q·p - c_p·q`), exact point location, SAT, and
//!   the area of a union of polygons by a vertical-slab sweep;
//! - [`properties`]: the seven properties and their runner;
//! - [`regressions`]: cases the properties once failed, each named after the behaviour it keeps.
//!
//! The set checked is the one `--method coverage` draws for opaque scenes (the depth-aware coverage
//! map); property 6 holds the BSP walk's set against it, property 7 every exact strategy of the
//! method registry.
//!
//! Normal run (2,000 cases per property, 500 for `strategies_agree`: 12,500 in all; a fixed RNG
//! seed per property unless PROPTEST_RNG_SEED is set):
//!     cargo test --release --test visible_set
//! Long run (SIGHTLINE_PROP_CASES per property, default 200,000; random seeds):
//!     SIGHTLINE_PROP_CASES=200000 cargo test --release --test visible_set -- --ignored _long
//! A failure prints its minimal `Case { kind, n, seed }`: the scene, camera and cull mode all
//! follow from it (`generators::setup`); such a case goes into [`regressions`] as a named test.
//! No proptest regression file is kept here: every runner sets `failure_persistence: None`
//! (were one kept, proptest would look for it in `tests/proptest-regressions/`, since this
//! directory has a `main.rs`).
//!
//! [`VisibleSet`]: sightline::visibility::VisibleSet

#[path = "../support/mod.rs"]
mod support;

mod generators;
mod oracle;
mod properties;
mod regressions;
