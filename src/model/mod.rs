//! The 5D sample model (see `docs/model.md`): a moving, defocused triangle in
//! clip space, an optional thin-lens camera it came from, screen tiles and samples.

pub mod camera;
pub mod case;
pub mod sample;
pub mod samples;
pub mod tile;
pub mod triangle;

pub use camera::ThinLens;
pub use case::Case;
pub use sample::Sample;
pub use samples::{SampleSet, Snap, Viewport};
pub use tile::Tile;
pub use triangle::{Dims, Triangle};

/// A value the model refuses, with the field it came from.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    #[error("field `{field}` = {value} is not a finite number")]
    NotFinite { field: String, value: String },
    #[error("field `{field}` = {value}: {why}")]
    OutOfRange { field: String, value: String, why: &'static str },
}

pub(crate) fn finite(field: impl Into<String>, v: f32) -> Result<(), ModelError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(ModelError::NotFinite { field: field.into(), value: format!("{v}") })
    }
}
