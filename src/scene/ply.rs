//! PLY loader (not yet written).

use super::Scene;
use crate::error::LoadError;

pub(super) fn load(bytes: &[u8], name: &str) -> Result<Scene, LoadError> {
    let _ = bytes;
    Err(LoadError::file(name, "PLY loader not yet written"))
}
