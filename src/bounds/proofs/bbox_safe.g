# bbox-safe: every padded corner value encloses the exact one (src/bounds/bbox.rs,
# `aabb_safe`; derivation in docs/proofs.md, "bbox-safe"). The code's constants
# (tests/proofs.rs checks them, and the formula, against the code):
PAD = 1b-21;
FLOOR = 1b-120;
STEPS = 4;
# The error model, lemmas STEP and ULP (step.smt2, ulp.smt2): every finite f32 rounding
# r of an exact z has |r - z| <= U |r| + E.
U = 1b-23;
E = 1b-149;
#
# The corner: s = RN(k c) (s = c on the x axis), n = RN(a +- s), q = RN(n / w) and the
# exact X = (a +- k c) / w; the pad p = RN(RN(RN(RN(|s| + |n|) + FLOOR) / w) * PAD).
# With T = |s| + |n|, lambda = |n| / T in [0, 1], V = 1 / w > 0 and B = T V, the model
# gives (each rounding r = z + rho |r| + theta E, |rho| <= U, |theta| <= 1):
#   q - X <= (U / (1 - U) + U) lambda B + U (1 - lambda) B + E (1 + U / (1 - U)) + 2 E V
#   p     >= PAD (B - E V) / (1+U)^4 + PAD (FLOOR - E) V / (1+U)^3 - PAD E / (1+U)^2 - E / (1+U)
# so q - X - p <= g1 B + g2 V + g3, and X - q - p the same. The padded end
# next_down^STEPS(RN(q - p)) is <= q - p - (STEPS - 1) 2^-149 (lemmas STEP and GAP), so it
# is <= X when g1 <= 0, g2 <= 0 and g3 <= (STEPS - 1) 2^-149: B >= 0 and V > 0 need no
# further range, so this holds for every finite input with w > 0.
g1 = (U / (1 - U) + U) * lambda + U * (1 - lambda) - PAD / ((1 + U) * (1 + U) * (1 + U) * (1 + U));
g2 = 2 * E + PAD * E / ((1 + U) * (1 + U) * (1 + U) * (1 + U))
     - PAD * (FLOOR - E) / ((1 + U) * (1 + U) * (1 + U));
g3 = E * (1 + U / (1 - U)) + PAD * E / ((1 + U) * (1 + U)) + E / (1 + U);
slack = (STEPS - 1) * E;
{ lambda in [0, 1] -> g1 <= 0 /\ g2 <= 0 /\ g3 - slack <= 0 }
