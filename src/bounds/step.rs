//! One f32 step down or up, written as selects rather than early returns, so that a loop
//! over many values can run them side by side: the same bits as `f32::next_down` and
//! `f32::next_up` for every input (NaN stays the same NaN; the infinity in the direction
//! of the step stays; a zero steps to the smallest subnormal of that direction).

/// `x.next_down()`.
#[inline(always)]
pub(crate) fn dn(x: f32) -> f32 {
    let b = x.to_bits();
    let abs = b & 0x7fff_ffff;
    let stepped = if abs == 0 {
        0x8000_0001
    } else if b == abs {
        b.wrapping_sub(1)
    } else {
        b.wrapping_add(1)
    };
    if x.is_nan() || b == f32::NEG_INFINITY.to_bits() {
        x
    } else {
        f32::from_bits(stepped)
    }
}

/// `x.next_up()`.
#[inline(always)]
pub(crate) fn up(x: f32) -> f32 {
    -dn(-x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn check(x: f32) {
        assert_eq!(dn(x).to_bits(), x.next_down().to_bits(), "dn({x:e}) [{:#x}]", x.to_bits());
        assert_eq!(up(x).to_bits(), x.next_up().to_bits(), "up({x:e}) [{:#x}]", x.to_bits());
    }

    #[test]
    fn steps_are_the_std_steps_bit_for_bit() {
        let special = [
            0.0,
            -0.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::from_bits(0x8000_0001),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::from_bits(0x7fc0_1234),
            1.0,
            -1.0,
        ];
        for x in special {
            check(x);
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for _ in 0..1_000_000 {
            check(f32::from_bits(rng.gen()));
        }
    }
}
