//! X3D loader (not yet written).

use super::Scene;
use crate::error::LoadError;

pub(super) fn load(bytes: &[u8], name: &str) -> Result<Scene, LoadError> {
    let _ = bytes;
    Err(LoadError::file(name, "X3D loader not yet written"))
}
