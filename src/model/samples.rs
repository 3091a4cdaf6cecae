//! The samples a bound promises to keep (see `docs/model.md`, §7): the sample set, the
//! optional vertex snapping and the viewport.
//!
//! - [`SampleSet`]: which pixel positions `(x, y)` a sample may have. [`SampleSet::Any`]
//!   (every position, the stochastic case and the default), pixel centres, a standard
//!   MSAA pattern, or a fixed-point grid. Lens position and time stay continuous.
//! - [`Snap`]: each vertex's pixel position at each motion key moved to a fixed-point
//!   grid before coverage is judged (coverage is then that of the snapped triangle).
//! - [`Viewport`]: the screen rectangle (and guard band) the cases are placed in.
//!
//! Each has a short text form (`any`, `centres`, `msaa4`, `grid8`; `8` for a snap;
//! `1920x1080+64` for a viewport) parsed by [`FromStr`] and printed by `Display`: the
//! command line, the corpus files and the reports all use it.

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;

/// The standard 2-sample pattern (the D3D / Vulkan standard sample positions): offsets
/// from the pixel centre in sixteenths of a pixel.
pub const MSAA2: [(i8, i8); 2] = [(4, 4), (-4, -4)];
/// The standard 4-sample pattern (a rotated grid), sixteenths from the pixel centre.
pub const MSAA4: [(i8, i8); 4] = [(-2, -6), (6, -2), (-6, 2), (2, 6)];
/// The standard 8-sample pattern, sixteenths from the pixel centre.
pub const MSAA8: [(i8, i8); 8] = [(1, -3), (-1, 3), (5, 1), (-3, -5), (-5, 5), (-7, -1), (3, 7), (7, -7)];
/// The standard 16-sample pattern, sixteenths from the pixel centre (one sample lies on
/// the pixel's left edge: offset -8).
pub const MSAA16: [(i8, i8); 16] = [
    (1, 1),
    (-1, -3),
    (-3, 2),
    (4, -1),
    (-5, -2),
    (2, 5),
    (5, 3),
    (3, -5),
    (-2, 6),
    (0, -7),
    (-4, -6),
    (-6, 4),
    (-8, 0),
    (7, -4),
    (6, 7),
    (-7, -8),
];

/// The largest grid and snap precision, in bits below the pixel: 2^-16 px. Finer grids
/// gain nothing over f32 positions near the origin and would leave the exact range of
/// the snapped coordinates (see [`snap_coord`]).
pub const MAX_BITS: u32 = 16;

/// Which pixel positions `(x, y)` the samples of a run may have. A pixel is the unit
/// square `[i, i + 1) x [j, j + 1)` for integers i, j.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SampleSet {
    /// Every position: the stochastic case (the default).
    #[default]
    Any,
    /// The pixel centres `(i + 1/2, j + 1/2)`.
    PixelCentres,
    /// The standard MSAA pattern of this many samples (2, 4, 8 or 16) in every pixel.
    Msaa(u8),
    /// The fixed-point grid `(a 2^-bits, b 2^-bits)` for integers a, b (`bits` at most
    /// [`MAX_BITS`]).
    Grid(u32),
}

impl SampleSet {
    /// The MSAA offsets (sixteenths of a pixel from its centre) of a pattern, or None
    /// when the set is not an MSAA pattern.
    pub fn msaa_offsets(self) -> Option<&'static [(i8, i8)]> {
        match self {
            SampleSet::Msaa(2) => Some(&MSAA2),
            SampleSet::Msaa(4) => Some(&MSAA4),
            SampleSet::Msaa(8) => Some(&MSAA8),
            SampleSet::Msaa(16) => Some(&MSAA16),
            _ => None,
        }
    }

    /// True for [`SampleSet::Any`].
    pub fn is_any(self) -> bool {
        self == SampleSet::Any
    }

    /// How many points of the set lie in the closed rectangle `[x0, x1] x [y0, y1]`
    /// (None for `Any`: a continuum).
    pub fn count_in(self, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<u128> {
        let n = |lo: f64, hi: f64, step: f64, off: f64| -> u128 {
            // integers k with lo <= k step + off <= hi
            let a = ((lo - off) / step).ceil();
            let b = ((hi - off) / step).floor();
            if b >= a {
                (b - a) as u128 + 1
            } else {
                0
            }
        };
        match self {
            SampleSet::Any => None,
            SampleSet::PixelCentres => Some(n(x0, x1, 1.0, 0.5) * n(y0, y1, 1.0, 0.5)),
            SampleSet::Grid(b) => {
                let s = (-(b as f64)).exp2();
                Some(n(x0, x1, s, 0.0) * n(y0, y1, s, 0.0))
            }
            SampleSet::Msaa(_) => {
                let offs = self.msaa_offsets().unwrap_or(&[]);
                let mut c = 0u128;
                for &(dx, dy) in offs {
                    let ox = (8 + dx as i32) as f64 / 16.0;
                    let oy = (8 + dy as i32) as f64 / 16.0;
                    c += n(x0, x1, 1.0, ox) * n(y0, y1, 1.0, oy);
                }
                Some(c)
            }
        }
    }

    /// The points of the set in the closed rectangle `[x0, x1] x [y0, y1]`, row by row
    /// (None for `Any`). Callers bound the count first with [`count_in`](Self::count_in).
    pub fn points_in(self, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<Vec<(f64, f64)>> {
        let axis = |lo: f64, hi: f64, step: f64, off: f64| -> Vec<f64> {
            let a = ((lo - off) / step).ceil() as i64;
            let b = ((hi - off) / step).floor() as i64;
            (a..=b).map(|k| k as f64 * step + off).filter(|&p| lo <= p && p <= hi).collect()
        };
        let grid = |step: f64, ox: f64, oy: f64| -> Vec<(f64, f64)> {
            let xs = axis(x0, x1, step, ox);
            axis(y0, y1, step, oy).into_iter().flat_map(|y| xs.iter().map(move |&x| (x, y))).collect()
        };
        match self {
            SampleSet::Any => None,
            SampleSet::PixelCentres => Some(grid(1.0, 0.5, 0.5)),
            SampleSet::Grid(b) => Some(grid((-(b as f64)).exp2(), 0.0, 0.0)),
            SampleSet::Msaa(_) => {
                let mut out = Vec::new();
                for &(dx, dy) in self.msaa_offsets().unwrap_or(&[]) {
                    out.extend(grid(1.0, (8 + dx as i32) as f64 / 16.0, (8 + dy as i32) as f64 / 16.0));
                }
                out.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
                Some(out)
            }
        }
    }

    /// True when `(x, y)` is a point of the set.
    pub fn contains(self, x: f64, y: f64) -> bool {
        let on = |p: f64, step: f64, off: f64| ((p - off) / step).fract() == 0.0 && ((p - off) / step).is_finite();
        match self {
            SampleSet::Any => x.is_finite() && y.is_finite(),
            SampleSet::PixelCentres => on(x, 1.0, 0.5) && on(y, 1.0, 0.5),
            SampleSet::Grid(b) => on(x, (-(b as f64)).exp2(), 0.0) && on(y, (-(b as f64)).exp2(), 0.0),
            SampleSet::Msaa(_) => self.msaa_offsets().unwrap_or(&[]).iter().any(|&(dx, dy)| {
                on(x, 1.0, (8 + dx as i32) as f64 / 16.0) && on(y, 1.0, (8 + dy as i32) as f64 / 16.0)
            }),
        }
    }

    /// The points of the set nearest `(x, y)`: those among the few set points around
    /// it (the grid cell's corners, the pixel's centre or pattern and its neighbours'),
    /// nearest first.
    pub fn near(self, x: f64, y: f64) -> Vec<(f64, f64)> {
        let r = match self {
            SampleSet::Any => return vec![(x, y)],
            SampleSet::Grid(b) => (-(b as f64)).exp2(),
            _ => 1.0,
        };
        let mut pts = self.points_in(x - r, x + r, y - r, y + r).unwrap_or_default();
        let d = |p: &(f64, f64)| (p.0 - x).powi(2) + (p.1 - y).powi(2);
        pts.sort_by(|a, b| d(a).total_cmp(&d(b)));
        pts
    }
}

/// True for [`SampleSet::Any`] (for serde's `skip_serializing_if`).
pub fn is_any(s: &SampleSet) -> bool {
    s.is_any()
}

impl fmt::Display for SampleSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SampleSet::Any => write!(f, "any"),
            SampleSet::PixelCentres => write!(f, "centres"),
            SampleSet::Msaa(n) => write!(f, "msaa{n}"),
            SampleSet::Grid(b) => write!(f, "grid{b}"),
        }
    }
}

/// A text form the parsers refuse, with why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{value}`: {why}")]
pub struct ParseError {
    pub value: String,
    pub why: String,
}

fn perr(value: &str, why: impl Into<String>) -> ParseError {
    ParseError { value: value.to_string(), why: why.into() }
}

fn bits(value: &str, s: &str) -> Result<u32, ParseError> {
    let b: u32 = s.parse().map_err(|_| perr(value, format!("expected a whole number of bits, 0 to {MAX_BITS}")))?;
    if b > MAX_BITS {
        return Err(perr(value, format!("at most {MAX_BITS} bits below the pixel")));
    }
    Ok(b)
}

impl FromStr for SampleSet {
    type Err = ParseError;
    fn from_str(s: &str) -> Result<Self, ParseError> {
        let t = s.trim();
        let help = "expected any, centres, msaa2, msaa4, msaa8, msaa16 or gridN (N bits below the pixel)";
        match t {
            "any" => Ok(SampleSet::Any),
            "centres" | "centers" | "pixel-centres" => Ok(SampleSet::PixelCentres),
            _ if t.starts_with("msaa") => match &t[4..] {
                "2" => Ok(SampleSet::Msaa(2)),
                "4" => Ok(SampleSet::Msaa(4)),
                "8" => Ok(SampleSet::Msaa(8)),
                "16" => Ok(SampleSet::Msaa(16)),
                _ => Err(perr(s, "the standard MSAA patterns have 2, 4, 8 or 16 samples")),
            },
            _ if t.starts_with("grid") => Ok(SampleSet::Grid(bits(s, &t[4..])?)),
            _ => Err(perr(s, help)),
        }
    }
}

impl Serialize for SampleSet {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for SampleSet {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// Vertex snapping: each vertex's pixel position `(x/w, y/w)` at each motion key moved
/// to the nearest point of the grid of `2^-bits` px (ties to even), w kept. See
/// [`snap_coord`] for how the snapped vertex is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Snap {
    pub bits: u32,
}

impl FromStr for Snap {
    type Err = ParseError;
    fn from_str(s: &str) -> Result<Self, ParseError> {
        Ok(Snap { bits: bits(s, s.trim())? })
    }
}

impl fmt::Display for Snap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.bits)
    }
}

/// The snapped clip coordinate of one vertex key: `g w` where `g` is `c / w` rounded to
/// the nearest multiple of `2^-bits` (ties to the even multiple), computed exactly.
/// Returns the exact value as f64 (None when `w <= 0`, when `c / w` is beyond
/// `2^(52 - 24 - bits)` px, where `g w` would not be exact in f64, or when an input is not
/// finite).
///
/// Exactness: `c` and `w` are f32 (24-bit significands); the multiple `m` of `2^-bits`
/// is found from the f64 quotient and then corrected by exact comparisons of `m w`
/// with `c` (products of an integer below 2^(52-24) and a 24-bit significand are exact
/// in f64), and `g w = m w 2^-bits` is exact for the same reason.
pub fn snap_coord(c: f32, w: f32, bits: u32) -> Option<f64> {
    if !(c.is_finite() && w.is_finite()) || w <= 0.0 {
        return None;
    }
    let scale = (bits as f64).exp2();
    let (c, w) = (c as f64 * scale, w as f64); // exact: a power of two
    let limit = (52.0f64 - 24.0).exp2();
    let mut m = (c / w).round();
    let in_range = |m: f64| m.abs() < limit; // false for NaN too
    if !in_range(m) {
        return None;
    }
    // Make m the nearest integer to c / w exactly: compare c with (m +- 1/2) w, both
    // exact (2m + 1 below 2^29, w 24 bits).
    loop {
        let hi = (2.0 * m + 1.0) * w; // 2 (m + 1/2) w
        let lo = (2.0 * m - 1.0) * w;
        let c2 = 2.0 * c;
        if c2 > hi || (c2 == hi && (m as i64) % 2 != 0) {
            m += 1.0;
        } else if c2 < lo || (c2 == lo && (m as i64) % 2 != 0) {
            m -= 1.0;
        } else {
            break;
        }
        if !in_range(m) {
            return None;
        }
    }
    Some(m * w / scale)
}

/// The screen rectangle `[x0, x0 + width] x [y0, y0 + height]` in pixels (the origin is
/// 0 unless stated: hardware whose fixed-point range is centred on the origin states
/// `-32768,-32768,65536x65536`), and a guard band of `guard` pixels around it: cases are
/// placed so that every vertex, at both motion keys and every lens corner, lies in front
/// of the lens and inside the guard-band rectangle, and tiles inside the viewport.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Viewport {
    pub x0: i32,
    pub y0: i32,
    pub width: u32,
    pub height: u32,
    pub guard: u32,
}

/// The largest viewport side and guard band the parser accepts (pixels): 2^17, and every
/// edge of the guard-band rectangle within +-2^17 of the origin. Pixel positions there are
/// whole numbers far below 2^24, exact in f32; whether a case can be snapped to a
/// sub-pixel grid at such positions is decided per case (a case that cannot be snapped is
/// not judged).
pub const MAX_VIEWPORT: u32 = 1 << 17;

impl Viewport {
    /// `[0, width] x [0, height]` with a guard band.
    pub fn sized(width: u32, height: u32, guard: u32) -> Self {
        Viewport { x0: 0, y0: 0, width, height, guard }
    }
    /// The guard-band rectangle `[x0, x1, y0, y1]`.
    pub fn guard_rect(&self) -> [f64; 4] {
        let g = self.guard as f64;
        let [x0, x1, y0, y1] = self.rect();
        [x0 - g, x1 + g, y0 - g, y1 + g]
    }
    /// The viewport rectangle `[x0, x1, y0, y1]`.
    pub fn rect(&self) -> [f64; 4] {
        let (x0, y0) = (self.x0 as f64, self.y0 as f64);
        [x0, x0 + self.width as f64, y0, y0 + self.height as f64]
    }
    /// True when the tile lies in the viewport.
    pub fn holds_tile(&self, t: &super::Tile) -> bool {
        let [x0, x1, y0, y1] = self.rect();
        t.x0 as f64 >= x0 && t.y0 as f64 >= y0 && t.x1 as f64 <= x1 && t.y1 as f64 <= y1
    }
}

impl fmt::Display for Viewport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.x0 != 0 || self.y0 != 0 {
            write!(f, "{},{},", self.x0, self.y0)?;
        }
        write!(f, "{}x{}", self.width, self.height)?;
        if self.guard > 0 {
            write!(f, "+{}", self.guard)?;
        }
        Ok(())
    }
}

impl FromStr for Viewport {
    type Err = ParseError;
    fn from_str(s: &str) -> Result<Self, ParseError> {
        let t = s.trim();
        let help = "expected WIDTHxHEIGHT[+GUARD] (from the origin), X,Y,WIDTHxHEIGHT[+GUARD] (from the \
                    corner (X, Y)) or centred:WIDTHxHEIGHT[+GUARD] (around the origin), in whole pixels, e.g. \
                    1920x1080+64 or -32768,-32768,65536x65536";
        // The origin: stated, centred, or 0.
        enum Origin {
            At(i64, i64),
            Centred,
        }
        let (origin, rest) = if let Some(r) = t.strip_prefix("centred:") {
            (Origin::Centred, r)
        } else {
            let parts: Vec<&str> = t.splitn(3, ',').collect();
            match parts.as_slice() {
                [x, y, r] => {
                    let x: i64 = x.trim().parse().map_err(|_| perr(s, help))?;
                    let y: i64 = y.trim().parse().map_err(|_| perr(s, help))?;
                    (Origin::At(x, y), *r)
                }
                [_] => (Origin::At(0, 0), t),
                _ => return Err(perr(s, help)),
            }
        };
        let (dims, guard) = match rest.split_once('+') {
            Some((d, g)) => (d, g.trim().parse::<u32>().map_err(|_| perr(s, help))?),
            None => (rest, 0),
        };
        let (w, h) = dims.split_once('x').ok_or_else(|| perr(s, help))?;
        let w: u32 = w.trim().parse().map_err(|_| perr(s, help))?;
        let h: u32 = h.trim().parse().map_err(|_| perr(s, help))?;
        if w == 0 || h == 0 {
            return Err(perr(s, "the viewport must be at least 1x1 pixels"));
        }
        if w > MAX_VIEWPORT || h > MAX_VIEWPORT || guard > MAX_VIEWPORT {
            return Err(perr(s, format!("each side and the guard band at most {MAX_VIEWPORT} pixels")));
        }
        let (x0, y0) = match origin {
            Origin::At(x, y) => (x, y),
            Origin::Centred => (-(w as i64 / 2), -(h as i64 / 2)),
        };
        let lim = MAX_VIEWPORT as i64;
        let g = guard as i64;
        if x0 - g < -lim || y0 - g < -lim || x0 + w as i64 + g > lim || y0 + h as i64 + g > lim {
            return Err(perr(
                s,
                format!("the guard-band rectangle must lie within +-{MAX_VIEWPORT} pixels of the origin"),
            ));
        }
        Ok(Viewport { x0: x0 as i32, y0: y0 as i32, width: w, height: h, guard })
    }
}

impl Serialize for Viewport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for Viewport {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_forms_round_trip_and_bad_ones_are_named() {
        for s in ["any", "centres", "msaa2", "msaa4", "msaa8", "msaa16", "grid0", "grid8", "grid16"] {
            assert_eq!(s.parse::<SampleSet>().unwrap().to_string(), s);
        }
        for s in ["msaa3", "msaa", "grid17", "gridx", "", "centre"] {
            let e = s.parse::<SampleSet>().unwrap_err().to_string();
            assert!(e.contains(&format!("`{s}`")), "{e}");
        }
        for s in ["1920x1080", "1920x1080+64", "1x1", "-32768,-32768,65536x65536", "-100,20,64x32+8"] {
            assert_eq!(s.parse::<Viewport>().unwrap().to_string(), s);
        }
        let c: Viewport = "centred:65536x65536+1024".parse().unwrap();
        assert_eq!((c.x0, c.y0, c.width, c.height, c.guard), (-32768, -32768, 65536, 65536, 1024));
        assert_eq!(c.rect(), [-32768.0, 32768.0, -32768.0, 32768.0]);
        for s in [
            "0x5",
            "1920",
            "1920x",
            "ax3",
            "300000x3",
            "3x3+a",
            "-3x3",
            "1,2x3",
            "a,0,3x3",
            "131072,0,3x3",
            "-131072,0,3x3+1",
            "0,0,0,3x3",
        ] {
            let e = s.parse::<Viewport>().unwrap_err().to_string();
            assert!(e.contains(&format!("`{s}`")), "{s}: {e}");
        }
        assert_eq!("8".parse::<Snap>().unwrap(), Snap { bits: 8 });
        assert!("17".parse::<Snap>().is_err() && "-1".parse::<Snap>().is_err());
    }

    #[test]
    fn msaa_patterns_are_distinct_sixteenths_inside_the_pixel() {
        for n in [2u8, 4, 8, 16] {
            let offs = SampleSet::Msaa(n).msaa_offsets().unwrap();
            assert_eq!(offs.len(), n as usize);
            for (i, a) in offs.iter().enumerate() {
                assert!((-8..8).contains(&a.0) && (-8..8).contains(&a.1), "{a:?}");
                assert!(offs[..i].iter().all(|b| b != a));
            }
            // Every row and every column of the pattern holds one sample (the patterns
            // are rotated grids / n-rooks patterns).
            let mut xs: Vec<i8> = offs.iter().map(|a| a.0).collect();
            xs.sort();
            xs.dedup();
            assert_eq!(xs.len(), n as usize, "msaa{n}");
            // One pixel holds n points; counting and listing agree.
            let s = SampleSet::Msaa(n);
            assert_eq!(s.count_in(3.0, 3.999, -2.0, -1.001), Some(n as u128));
            let pts = s.points_in(3.0, 3.999, -2.0, -1.001).unwrap();
            assert_eq!(pts.len(), n as usize);
            assert!(pts.iter().all(|&(x, y)| s.contains(x, y)));
        }
    }

    #[test]
    fn sets_count_list_and_contain_their_points() {
        let c = SampleSet::PixelCentres;
        assert_eq!(c.count_in(0.0, 4.0, 0.0, 4.0), Some(16));
        assert_eq!(c.points_in(0.0, 1.0, 0.0, 1.0).unwrap(), vec![(0.5, 0.5)]);
        assert!(c.contains(2.5, -3.5) && !c.contains(2.0, 2.5));
        let g = SampleSet::Grid(2);
        assert_eq!(g.count_in(0.0, 1.0, 0.0, 1.0), Some(25)); // closed tile: 5 x 5
        assert!(g.contains(0.25, 0.75) && !g.contains(0.125, 0.0));
        assert_eq!(g.near(0.3, 0.1)[0], (0.25, 0.0));
        assert_eq!(c.near(0.9, 0.2)[0], (0.5, 0.5));
        assert_eq!(SampleSet::Any.count_in(0.0, 1.0, 0.0, 1.0), None);
    }

    #[test]
    fn snapping_is_exact_round_to_nearest_ties_to_even() {
        // x/w = 1.3 px, 2 bits: nearest quarter is 1.25.
        assert_eq!(snap_coord(2.6, 2.0, 2), Some(2.5));
        // Ties: 0.125 at 2 bits lies between 0 and 0.25: to the even multiple (0).
        assert_eq!(snap_coord(0.125, 1.0, 2), Some(0.0));
        assert_eq!(snap_coord(0.375, 1.0, 2), Some(0.5));
        assert_eq!(snap_coord(-0.375, 1.0, 2), Some(-0.5));
        // A quotient not exact in f64: 1/3 px at 0 bits is 0, 2/3 px is 1.
        assert_eq!(snap_coord(1.0, 3.0, 0), Some(0.0));
        assert_eq!(snap_coord(2.0, 3.0, 0), Some(3.0));
        // The snapped pixel position is exactly on the grid.
        let w = 0.7f32;
        let s = snap_coord(123.456, w, 8).unwrap();
        let g = s / w as f64 * 256.0;
        assert!((g - g.round()).abs() < 1e-6, "{g}");
        assert_eq!(snap_coord(1.0, 0.0, 8), None);
        assert_eq!(snap_coord(1.0, -1.0, 8), None);
        assert_eq!(snap_coord(1e30, 1.0, 8), None);
    }
}
