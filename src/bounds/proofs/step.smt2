; Lemma STEP: a value rounded to nearest, stepped one f32 outward, encloses what was
; rounded. For every z of W, with R the bits of r = RN_f32(z) or of any finite nearest
; f32 of z (ties either way): next_down(r) <= z <= next_up(r), and z lies between
; the neighbours of r on the grid continued past MAX (wnd, wnu: -MAX rounds only
; values above -2^128, MAX only values below 2^128). Covers subnormal results
; (underflow), zeros of either sign and overflow to +-inf (next_down(+inf) = MAX).
(declare-const z W)
(declare-const R (_ BitVec 32))
(assert (not (fp.isNaN z)))
(assert (or (= (f R) (rn z)) (near z (f R))))
(assert (not (and (fp.leq (wide (f (nd R))) z) (fp.leq z (wide (f (nu R))))
                  (or (fp.isInfinite (f R)) (and (fp.leq (wnd R) z) (fp.leq z (wnu R)))))))
(check-sat)
