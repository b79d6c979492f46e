//! OBJ loader (not yet written).

use super::Scene;
use crate::error::LoadError;

pub(super) fn load(
    bytes: &[u8],
    name: &str,
    dir: Option<&std::path::Path>,
) -> Result<Scene, LoadError> {
    let _ = (bytes, dir);
    Err(LoadError::file(name, "OBJ loader not yet written"))
}
