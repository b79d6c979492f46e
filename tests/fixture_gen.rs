//! The generated fixtures (binary STL and PLY, and the STL/PLY cubes) match their generator in
//! `tests/support/generated.rs`. `SIGHTLINE_REGEN_FIXTURES=1 cargo test --test fixture_gen`
//! rewrites them.

mod support;

use support::fixtures::fixtures_dir;
use support::generated::generated_fixtures;

#[test]
fn generated_fixtures_are_up_to_date() {
    let regen = std::env::var_os("SIGHTLINE_REGEN_FIXTURES").is_some();
    for (path, bytes) in generated_fixtures() {
        let full = fixtures_dir().join(path);
        if regen {
            std::fs::write(&full, &bytes).unwrap();
        }
        let on_disk = std::fs::read(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()));
        assert!(
            on_disk == bytes,
            "{} differs from its generator; rerun with SIGHTLINE_REGEN_FIXTURES=1",
            full.display()
        );
    }
}
