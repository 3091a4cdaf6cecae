; Lemma MONO: rounding to nearest is monotone: z1 <= z2 implies RN(z1) <= RN(z2).
; With RN(0) = 0 it gives SIGN: the f32 difference of f32 values x >= y is >= 0.
(declare-const z1 W)
(declare-const z2 W)
(assert (not (fp.isNaN z1)))
(assert (not (fp.isNaN z2)))
(assert (fp.leq z1 z2))
(assert (not (fp.leq (rn z1) (rn z2))))
(check-sat)
