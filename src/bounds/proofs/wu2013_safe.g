# wu2013-safe: the padded f32 line evaluates at or above the exact line it pads
# (`safe_line` in src/bounds/wu2013/safe.rs, `TimeLine::eval`; derivation in
# docs/proofs.md, "wu2013-safe"). The code's constants (tests/proofs.rs checks them):
PAD = 1b-21;
FLOOR = 1b-100;
# The endpoints' limit: a line is built only when |e_left|, |e_right| <= LIMIT.
LIMIT = 1b100;
# The error model, lemmas STEP and ULP: every finite f32 rounding r of z has
# |r - z| <= U |r| + E.
U = 1b-23;
E = 1b-149;
#
# The line t = a l + b (f32 a, b) is padded to b' = next_up(RN(b + p)) with
# p = RN(RN(RN(RN(|a| + |a|) + |b|) + FLOOR) * PAD); eval computes x = RN(RN(a l) + b')
# for a lens coordinate |l| <= 1. With A = |a|, Bb = |b|, k = 1 / (1 - U), h = 1 / (1 + U):
#   x - (a l + b) >= p - U |m| - U |x| - 2 E           (m = RN(a l); b' >= b + p by STEP)
#   p   >= 2 PAD h^4 A + PAD h^3 Bb + PAD h^2 FLOOR - PAD E (h^4 + h^3 + h^2) - E h
#   p   <= 2 PAD k^4 A + PAD k^3 Bb + PAD k^2 FLOOR + PAD E (k^4 + k^3 + k^2) + E k
#   |m| <= k (A + E),  |b'| <= (1 + U) k (Bb + p + E) + E,  |x| <= k (|m| + |b'| + E)
# so x - (a l + b) >= cA A + cB Bb + c0, and the upper line's eval is >= 0 for every
# covered sample (t <= a l + b <= x, and RN of a non-negative difference is >= 0 by MONO)
# when cA, cB, c0 >= 0; the lower line is the mirror image. A, Bb >= 0: no range needed.
k = 1 / (1 - U);
h = 1 / (1 + U);
phiA = 2 * PAD * k * k * k * k;
phiB = PAD * k * k * k;
phi0 = PAD * k * k * FLOOR + PAD * E * (k * k * k * k + k * k * k + k * k) + E * k;
# |x| <= xA A + xB Bb + x0 (through |m| and |b'| with p's upper bound)
xA = k * (k + (1 + U) * k * phiA);
xB = k * ((1 + U) * k * (1 + phiB));
x0 = k * (k * E + (1 + U) * k * (phi0 + E) + E + E);
cA = 2 * PAD * h * h * h * h - U * k - U * xA;
cB = PAD * h * h * h - U * xB;
c0 = PAD * h * h * FLOOR - PAD * E * (h * h * h * h + h * h * h + h * h) - E * h - U * k * E - U * x0 - 2 * E;
#
# Finiteness. With |e_left|, |e_right| <= LIMIT: 0.5 e is exact or a subnormal rounding
# (|RN(0.5 e)| <= LIMIT / 2), so A = |RN(RN(0.5 e_right) - RN(0.5 e_left))| <= LIMIT
# (LIMIT is an f32 value and rounding is monotone, MONO); |e + a| <= 2 LIMIT, so
# Bb = |b| <= next_up(2 LIMIT) <= 2 LIMIT (1 + 2U). Every other rounded value of the
# chain (p, RN(b + p), b', m, x) is at most |x|'s bound below, far under the overflow
# threshold 2^128 (1 - 2^-25): no rounding of the chain overflows, so x is finite and
# the error model above applies to each of them.
xmax = xA * LIMIT + xB * (2 * LIMIT * (1 + 2 * U)) + x0;
{ cA >= 0 /\ cB >= 0 /\ c0 >= 0 /\ xmax <= 1b104 }
