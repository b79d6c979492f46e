//! STL loader (not yet written).

use super::Scene;
use crate::error::LoadError;

pub(super) fn load(bytes: &[u8], name: &str) -> Result<Scene, LoadError> {
    let _ = bytes;
    Err(LoadError::file(name, "STL loader not yet written"))
}
