//! Certified tile extents: enclosures of the infimum and supremum of u, v, t and the hit
//! depth over the interior-covered samples of a tile, or a certificate that none is
//! covered.
//!
//! # Method
//! Best-first branch-and-bound over boxes of (x, y, u, v, t), one search per extent ([`Extent`]).
//! A box is judged from enclosures of the four coverage polynomials (E_0, E_1, E_2, D)
//! over it:
//! - **empty** when one value is certainly <= 0 and another certainly >= 0 (or one is
//!   certainly 0): no sample in it can have four values of one strict sign;
//! - **full** when all four are certainly > 0 or all certainly < 0;
//! - **undecided** otherwise.
//!
//! The enclosures are tight because of the structure of the polynomials: for a fixed t
//! each `E_k` (and the depth numerator `N`) is affine in each of x, y, u, v separately
//! (`P_i.x` is affine in (x, u), `P_i.y` in (y, v), and `E_k` multiplies one of each),
//! and `D` is affine in each of u, v. A function affine in each variable separately
//! takes its extremes over a box at the box's corners, so the range over the box is the
//! hull over the 16 (x, y, u, v) corners of the range in t. In t each value is a
//! polynomial of degree <= 3, carried exactly as a polynomial in `s = t - t_mid` with
//! coefficients carrying rigorous rounding-error bounds ([`TPoly`]) and bounded over `s in [-h, h]`
//! term by term. All arithmetic rounds outward; nothing uses an epsilon. The 16 corners
//! are evaluated side by side in lanes (`LPoly`), each lane doing exactly what a
//! corner-by-corner loop would (a test holds the two to the same bits).
//!
//! For the hit depth a box has three enclosures: the corner quotients `N / D` (over
//! every sample of the box, covered or not), the hull of the vertex depths `z_k / w_k`
//! over the box's times, which holds every covered sample in front of the lens (see
//! [`BoxValues::vertex_depth`]), and the bound over the covered polygon
//! ([`BoxValues::covered_depth`], module `depth`): `(N +- sum lambda_k E_k) / D` with
//! multipliers from the linear programme at the box's middle (u, v, t), exact there
//! and first-order tight around it, whatever the signs of the `w_i`. A depth search
//! keys a box by the tightest.
//!
//! For a minimum (say of u) the search always splits the live box of smallest lower
//! bound `u_lo`; that `u_lo` is a certified lower bound of the infimum. Each undecided or
//! full box proposes witness samples (for an extent search: points of the covered
//! polygon at the box's middle (u, v, t), the depth's extreme vertex nudged inside, and
//! the box's (u, v, t) corners when those miss) that the exact classifier
//! ([`crate::coverage::classify`]) must confirm as interior; the best witness is a
//! certified upper bound. The search stops when the two meet within the resolution.
//! The extent searches eliminate (x, y) ([`Search::eliminate`]) and split only (u, v, t)
//! while they can; there, once a witness is known, a box across the resolution band
//! below it is cut at the band's edge, so only the part beyond the band needs ruling
//! out. (The side searches of the gate judge by the enclosures alone unless asked.) Boxes that reach the minimum size undecided, or remain when the box
//! budget runs out, are counted and reported, never dropped: the enclosure then runs
//! from the smallest lower bound among them. A full box (every sample interior) is
//! settled by its witness only when the witness reaches the box's key; otherwise it is
//! split like any other (the widest side when no value's smear points anywhere) or,
//! at the minimum size, kept as undecided. A depth search proposes a full box's
//! corners as witnesses: at a fixed time the depth is monotone in each of x, y, u, v
//! over it, so its extremes are at corners. (Dropping full boxes whose witness did not
//! reach their key once certified a least depth 4e-3 above an exactly interior sample
//! at the corner of a tile's domain, one vertex behind the lens; the independent
//! attack in `oracles/tests/attack_extents.rs` found it and holds the case.)
//!
//! Dimensions a triangle does not have are not searched: a static triangle is judged at
//! t = 0 and, when covered, its t extents are the whole requested range (coverage does
//! not depend on t); a pinhole triangle (every CoC zero) likewise in u and v.
//!
//! # Layout
//! - [`tpoly`]: the time polynomials of one box corner;
//! - `lanes`: the same polynomials for all corners of a box side by side;
//! - [`enclosure`]: the enclosures of the coverage values over a box and the judgement
//!   empty / full / undecided;
//! - `depth`: the bounds on the hit depth of the covered samples of a box by a
//!   combination of the depth with the edge values;
//! - `depth_plane`: depth ends over a whole tile by moving planes through the vertices;
//! - `elimination`: (x, y) decided exactly for a box of (u, v, t) (the covered pixels at
//!   a fixed lens position and time are a convex polygon), and witnesses from it;
//! - [`bnb`]: the best-first branch-and-bound engine (also used by the constraint
//!   search of the code that uses this crate);
//! - [`objective`]: the eight named extents and what a search needs to know of each;
//! - [`search`](mod@search): the search for one extent on the engine;
//! - [`solver`]: the tile solver that runs the searches on demand and keeps them.

pub mod bnb;
mod cut;
mod depth;
mod depth_direct;
mod depth_plane;
mod elimination;
pub mod enclosure;
mod lanes;
pub mod objective;
#[cfg(test)]
mod reference;
pub mod search;
pub mod solver;
#[cfg(test)]
mod testgen;
pub mod tpoly;

pub use cut::Cut;
pub use depth_direct::DepthNumerator;
pub use depth_plane::{depth_cuts, depth_end_by_planes, depth_plane_cuts, Slopes};

pub use elimination::clipped_point as covered_point;
pub use enclosure::{
    box_values, box_values_cutting, box_values_eliminating, box_values_with, classify_values, Box5, BoxClass, BoxValues,
};
pub use objective::Extent;
pub use search::{search, solve_objective, ExtentsConfig, Extreme, ObjectiveResult, Search};
pub use solver::{tile_extents, Occupancy, Side, TileExtents, TileSolver};
pub use tpoly::TPoly;
