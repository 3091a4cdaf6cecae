//! The inputs the encoded methods are compared on: physical cases of every regime with
//! tiles at their footprint's boundary and beside it, wild random triangles (coordinates
//! from subnormal to 1e30, w of either sign, exactly 0 or tiny, shears crossing or
//! touching 0) and the same with a NaN, an infinity or a signed zero planted in one
//! number of the triangle or the tile.

pub use cullproof::cases::generate::bit_compare_case as case;

/// The answer of a tile test bit for bit: every interval end's bits and every
/// constraint's debug form (which prints each f32 so that it reads back to the same
/// bits), or None for Empty.
pub fn bits(r: &cullproof::bounds::TileResult) -> Option<(Vec<u32>, String)> {
    match r {
        cullproof::bounds::TileResult::Empty => None,
        cullproof::bounds::TileResult::Bounds(b) => {
            let mut v: Vec<u32> = b.u.iter().chain(&b.v).chain(&b.t).map(|x| x.to_bits()).collect();
            v.extend(b.z.iter().flatten().map(|x| x.to_bits()));
            Some((v, format!("{:?}", b.constraints)))
        }
    }
}
