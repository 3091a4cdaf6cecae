; Lemma ULP: the neighbours of a finite f32 r (on the grid continued past MAX) are
; within 2^-23 |r| + 2^-149 of it. With STEP: every finite rounding r of z has
; |r - z| <= 2^-23 |r| + 2^-149, the error model of the running bounds (bbox_safe.g).
; The gaps are rounded up (in W; the scaling by 2^-23 is exact there), so UNSAT proves the exact claim.
(declare-const R (_ BitVec 32))
(assert (not (fp.isNaN (f R))))
(assert (not (fp.isInfinite (f R))))
(define-fun r () W (wide (f R)))
(define-fun u2 () W ((_ to_fp 11 53) RNE (/ 1.0 8388608.0)))
; The bound is the larger of the two terms (u2 |r| for a normal r, 2^-149 otherwise).
(define-fun normal () Bool (fp.leq (wide (f #x00800000)) (fp.abs r)))
(define-fun bound () W (ite normal (fp.mul RNE u2 (fp.abs r)) (wide (f #x00000001))))
(assert (not (and (fp.leq (fp.sub RTP (wnu R) r) bound) (fp.leq (fp.sub RTP r (wnd R)) bound))))
(check-sat)
