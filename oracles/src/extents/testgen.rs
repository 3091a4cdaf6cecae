//! Inputs shared by the unit tests of the extents: a reproducible number stream, random
//! moving and defocused triangles (any signs of `w`), and one behind-lens sliver.

use crate::tri::Tri;

/// Uniform numbers in [0, 1) from a xorshift stream (reproducible test inputs).
pub(super) fn unit_stream(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A moving, defocused triangle in clip space whose `w` may be negative or cross 0
/// during the shutter (one vertex in three on average behind the lens at some time).
pub(super) fn random_tri(next: &mut impl FnMut() -> f64) -> Tri {
    let mut v = |lo: f64, hi: f64| lo + (hi - lo) * next();
    let mut q = [[0.0; 4]; 3];
    let mut r = [[0.0; 4]; 3];
    let (mut c0, mut c1) = ([0.0; 3], [0.0; 3]);
    for i in 0..3 {
        q[i] = [v(-12.0, 12.0), v(-12.0, 12.0), v(-1.0, 1.0), v(-1.0, 2.5)];
        r[i] = [v(-12.0, 12.0), v(-12.0, 12.0), v(-1.0, 1.0), v(-1.0, 2.5)];
        c0[i] = v(-3.0, 3.0);
        c1[i] = v(-3.0, 3.0);
    }
    Tri { q, r, c0, c1, k: v(0.5, 2.0) }
}

/// [`random_tri`] with its third vertex moved within 0.3 px of the second (x and y) and,
/// with `near_w`, within 0.01 of it in `w` too: the nearly degenerate case, behind the
/// lens or not.
pub(super) fn random_sliver(next: &mut impl FnMut() -> f64, near_w: bool) -> Tri {
    let mut t = random_tri(next);
    let mut v = |lo: f64, hi: f64| lo + (hi - lo) * next();
    for j in 0..2 {
        t.q[2][j] = t.q[1][j] + v(-0.3, 0.3);
        t.r[2][j] = t.r[1][j] + v(-0.3, 0.3);
    }
    if near_w {
        (t.q[2][3], t.r[2][3]) = (t.q[1][3] + v(-0.01, 0.01), t.r[1][3] + v(-0.01, 0.01));
    }
    t
}

/// A sliver from a procedural scene: two vertices 0.6 px apart, the third behind the
/// lens; over the tile [39, 41] x [-46, -44] its covered set is a thin wedge.
pub(super) fn behind_lens_sliver() -> Tri {
    Tri {
        q: [
            [68.79700469970703, -11.174562454223633, -0.5078836679458618, -0.40783292055130005],
            [45.81073760986328, -51.95940399169922, 1.1483010053634644, 1.2481861114501953],
            [45.172698974609375, -51.340232849121094, 1.1456304788589478, 1.2455159425735474],
        ],
        r: [
            [71.16487884521484, -12.409738540649414, -0.5066049098968506, -0.40655428171157837],
            [47.85801696777344, -53.194580078125, 1.149579644203186, 1.249464750289917],
            [47.219970703125, -52.575408935546875, 1.146909236907959, 1.246794581413269],
        ],
        c0: [-11.117255210876465, -10.203001976013184, -10.204476356506348],
        c1: [-11.116549491882324, -10.202296257019043, -10.20376968383789],
        k: 1.0,
    }
}
