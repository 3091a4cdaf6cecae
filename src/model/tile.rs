//! A screen tile.

use super::{finite, ModelError};
use serde::{Deserialize, Serialize};

/// The pixel rectangle `[x0, x1] x [y0, y1]` (continuous pixel coordinates).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tile {
    pub x0: f32,
    pub y0: f32,
    pub x1: f32,
    pub y1: f32,
}

impl Tile {
    /// The `size x size` tile whose lower corner is (x0, y0).
    pub fn square(x0: f32, y0: f32, size: f32) -> Self {
        Tile { x0, y0, x1: x0 + size, y1: y0 + size }
    }
    pub fn validate(&self) -> Result<(), ModelError> {
        for (n, v) in [("x0", self.x0), ("y0", self.y0), ("x1", self.x1), ("y1", self.y1)] {
            finite(format!("tile.{n}"), v)?;
        }
        if self.x0 >= self.x1 {
            return Err(ModelError::OutOfRange {
                field: "tile.x1".into(),
                value: format!("{} (x0 = {})", self.x1, self.x0),
                why: "the tile is empty: x1 must be greater than x0",
            });
        }
        if self.y0 >= self.y1 {
            return Err(ModelError::OutOfRange {
                field: "tile.y1".into(),
                value: format!("{} (y0 = {})", self.y1, self.y0),
                why: "the tile is empty: y1 must be greater than y0",
            });
        }
        Ok(())
    }
    pub fn center(&self) -> (f32, f32) {
        (0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1))
    }
    pub fn contains(&self, x: f32, y: f32) -> bool {
        self.x0 <= x && x <= self.x1 && self.y0 <= y && y <= self.y1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn empty_tile_is_refused_by_name() {
        let e = Tile { x0: 2.0, y0: 0.0, x1: 2.0, y1: 1.0 }.validate().unwrap_err().to_string();
        assert!(e.contains("tile.x1") && e.contains("empty"), "{e}");
        assert!(Tile::square(0.0, 0.0, 2.0).validate().is_ok());
    }
}
