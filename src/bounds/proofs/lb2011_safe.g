# lb2011-safe: a patch's padded f32 value is at or above the exact patch through its
# corner values (`patch_of` in src/bounds/lb2011/safe.rs, `eval_of` in lb2011.rs;
# derivation in docs/proofs.md, "lb2011-safe"). The code's constants (tests/proofs.rs
# checks them):
PAD = 1b-18;
FLOOR = 1b-140;
# A patch is emitted only when M = max |g| < LIMIT.
LIMIT = 1b120;
# The error model, lemmas STEP and ULP: every finite f32 rounding r of z has
# |r - z| <= U |r| + E, so |r| <= k (|z| + E) and, for z >= 0, r >= h (z - E).
U = 1b-23;
E = 1b-149;
k = 1 / (1 - U);
h = 1 / (1 + U);
#
# The corner values g00, g10, g01, g11 (g[l][e] at l = -1, 1 and t = 0, 1) define the
# exact patch G = P + Q l + t (R + S l): P = (g00 + g10) / 2, Q = (g10 - g00) / 2,
# R = (g01 + g11) / 2 - P, S = (g11 - g01) / 2 - Q. For |l| <= 1 and t in [0, 1]:
# |P + Q l| <= M, |R + S l| <= 2 M (a difference of two such lines) and |G| <= M (G
# interpolates values in [-M, M] with weights >= 0 summing to 1).
# The code: p = RN(RN(g00 + g10) * 0.5), q = RN(RN(g10 - g00) * 0.5),
# r = RN(RN(RN(g01 + g11) * 0.5) - p), s = RN(RN(RN(g11 - g01) * 0.5) - q),
# pd = RN(RN(M * PAD) + FLOOR), P' = next_up(RN(p + pd)); per sample
# x1 = RN(q l), x2 = RN(P' + x1), x3 = RN(s l), x4 = RN(r + x3), x5 = RN(t x4),
# eval = x6 = RN(x2 + x5).
# Every bound below is linear in M: |x| <= xM M + x0 (and a difference D the same).
#
# s1 = RN(g00 + g10) (and the other three sums): |g00 + g10| <= 2 M.
s1M = 2 * k;
s10 = k * E;
# p = RN(s1 * 0.5) (and q, and the halves at t = 1): |p - P| <= Dp.
pM = k * s1M / 2;
p0 = k * (s10 / 2 + E);
DpM = U * pM + U * s1M / 2;
Dp0 = U * p0 + E + (U * s10 + E) / 2;
# r = RN(hp - p), hp the half-sum at t = 1 (and s): |hp - p| <= 2 M + 2 Dp, |r - R| <= Dr.
rM = k * (2 + 2 * DpM);
r0 = k * (2 * Dp0 + E);
DrM = U * rM + 2 * DpM;
Dr0 = U * r0 + E + 2 * Dp0;
# The coefficients' errors move the patch by at most Ec on the square.
EcM = 2 * DpM + 2 * DrM;
Ec0 = 2 * Dp0 + 2 * Dr0;
# The pad, from below (pd) and above (Pd).
pdM = h * h * PAD;
pd0 = h * FLOOR - h * h * E - h * E;
PdM = k * k * PAD;
Pd0 = k * (k * E + FLOOR + E);
# p2 = RN(p + pd), P' = next_up(p2) (STEP): p + pd <= P' <= p + pd + 2 U |p2| + 2 E.
p2M = k * (pM + PdM);
p20 = k * (p0 + Pd0 + E);
dM = PdM + 2 * U * p2M;
d0 = Pd0 + 2 * U * p20 + 2 * E;
# The evaluation; ei = U |xi| + E is the error of xi.
x1M = k * pM;
x10 = k * (p0 + E);
e1M = U * x1M;
e10 = U * x10 + E;
# |P' + x1| <= |P + Q l| + (P' - p) + |p - P| + |q - Q| + e1
x2M = k * (1 + dM + 2 * DpM + e1M);
x20 = k * (d0 + 2 * Dp0 + e10 + E);
e2M = U * x2M;
e20 = U * x20 + E;
x3M = k * rM;
x30 = k * (r0 + E);
e3M = U * x3M;
e30 = U * x30 + E;
# |r + x3| <= |R + S l| + |r - R| + |s - S| + e3
x4M = k * (2 + 2 * DrM + e3M);
x40 = k * (2 * Dr0 + e30 + E);
e4M = U * x4M;
e40 = U * x40 + E;
x5M = k * x4M;
x50 = k * (x40 + E);
e5M = U * x5M;
e50 = U * x50 + E;
# |x2 + x5| <= |G| + (P' - p) + Ec + e1 + ... + e5
x6M = k * (1 + dM + EcM + e1M + e2M + e3M + e4M + e5M);
x60 = k * (d0 + Ec0 + e10 + e20 + e30 + e40 + e50 + E);
e6M = U * x6M;
e60 = U * x60 + E;
# eval - G = (P' - P) + (q - Q) l + t ((r - R) + (s - S) l) + e1 + e2 + t (e3 + e4) + e5 + e6
#          >= pd - Ec - (e1 + ... + e6), so eval >= G for every M >= 0 when cM, c0 >= 0.
cM = pdM - EcM - (e1M + e2M + e3M + e4M + e5M + e6M);
c0 = pd0 - Ec0 - (e10 + e20 + e30 + e40 + e50 + e60);
# Finiteness: with M < LIMIT every rounded value of the chain is at most the sum of
# their bounds, below 2^125 and so far under the overflow threshold 2^128 (1 - 2^-25):
# no rounding overflows, each is finite and the error model applies to it (P' is at
# most one step above p2, within the same bound's slack).
xM = s1M + pM + rM + p2M + x1M + x2M + x3M + x4M + x5M + x6M;
x0 = s10 + p0 + r0 + p20 + x10 + x20 + x30 + x40 + x50 + x60;
xmax = xM * LIMIT + x0;
{ cM >= 0 /\ c0 >= 0 /\ xmax <= 1b125 }
