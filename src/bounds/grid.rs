//! The answers of one prepared method for every tile of a grid ([`Prepared::grid`]).
//!
//! A rasterizer walks the tiles under a triangle row by row, and many tile tests split
//! by axis: a part that reads only the tile's x range (its column) and a part that reads
//! only its y range (its row). Over a grid of `nx` columns and `ny` rows such a test
//! needs `nx + ny` axis parts and `nx * ny` cheap combinations instead of `2 nx ny`
//! axis parts. A method that shares work this way overrides [`Prepared::grid`]; every
//! other method gets [`PerTile`], which asks [`Prepared::tile`] tile by tile.
//!
//! The rule: [`TileGrid::tile`] answers exactly what [`Prepared::tile`] answers for
//! [`Grid::tile`] of the same indices, bit for bit, constraints included (a test,
//! `grid_tests.rs`, checks every registered method on physical and hostile inputs).

use super::{Prepared, TileResult};
use crate::model::Tile;

/// A grid of tiles: tile `(i, j)` spans columns `[xs[i], xs[i + 1]]` and rows
/// `[ys[j], ys[j + 1]]` (so `xs.len() - 1` columns and `ys.len() - 1` rows).
#[derive(Clone, Copy, Debug)]
pub struct Grid<'a> {
    pub xs: &'a [f32],
    pub ys: &'a [f32],
}

impl<'a> Grid<'a> {
    /// The grid over the given boundaries (each of at least two values).
    pub fn new(xs: &'a [f32], ys: &'a [f32]) -> Self {
        assert!(xs.len() >= 2 && ys.len() >= 2, "a grid needs at least two boundaries per axis");
        Grid { xs, ys }
    }
    /// The number of columns of tiles.
    pub fn columns(&self) -> usize {
        self.xs.len() - 1
    }
    /// The number of rows of tiles.
    pub fn rows(&self) -> usize {
        self.ys.len() - 1
    }
    /// Column `i`'s x range.
    pub fn column(&self, i: usize) -> [f32; 2] {
        [self.xs[i], self.xs[i + 1]]
    }
    /// Row `j`'s y range.
    pub fn row(&self, j: usize) -> [f32; 2] {
        [self.ys[j], self.ys[j + 1]]
    }
    /// Tile `(i, j)`.
    pub fn tile(&self, i: usize, j: usize) -> Tile {
        Tile { x0: self.xs[i], y0: self.ys[j], x1: self.xs[i + 1], y1: self.ys[j + 1] }
    }
}

/// One method's answers over a [`Grid`] (made by [`Prepared::grid`]).
pub trait TileGrid {
    /// The answer for tile `(i, j)` of the grid: what [`Prepared::tile`] answers for
    /// [`Grid::tile`]`(i, j)`.
    fn tile(&self, i: usize, j: usize) -> TileResult;
}

/// The grid of a method that shares nothing: [`Prepared::tile`] for each tile.
pub struct PerTile<'a, P: ?Sized> {
    pub prep: &'a P,
    pub grid: Grid<'a>,
}

impl<P: Prepared + ?Sized> TileGrid for PerTile<'_, P> {
    fn tile(&self, i: usize, j: usize) -> TileResult {
        self.prep.tile(&self.grid.tile(i, j))
    }
}
