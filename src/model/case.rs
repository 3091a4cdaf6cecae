//! A case: a triangle, and the thin lens it came from when it is physical.

use super::{ModelError, ThinLens, Triangle};
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    pub triangle: Triangle,
    /// Present when the triangle's CoC and aspect come from this thin lens; only such
    /// cases can also be judged by Embree. Absent for the per-vertex CoC variant.
    #[serde(default)]
    pub lens: Option<ThinLens>,
}

impl Case {
    pub fn validate(&self) -> Result<(), ModelError> {
        self.triangle.validate().map_err(|e| prefix("triangle", e))?;
        if let Some(l) = &self.lens {
            l.validate()?;
            l.check_matches(&self.triangle).map_err(|e| prefix("triangle", e))?;
        }
        Ok(())
    }
}

fn prefix(p: &str, e: ModelError) -> ModelError {
    match e {
        ModelError::NotFinite { field, value } => ModelError::NotFinite { field: format!("{p}.{field}"), value },
        ModelError::OutOfRange { field, value, why } => {
            ModelError::OutOfRange { field: format!("{p}.{field}"), value, why }
        }
    }
}
