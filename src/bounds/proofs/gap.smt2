; Lemma GAP: a step moves by at least 2^-149: next_down(x) <= x - 2^-149 and
; next_up(x) >= x + 2^-149 for every finite f32 x (the subtraction and the sum are
; rounded in W towards the side that makes UNSAT a proof).
(declare-const X (_ BitVec 32))
(assert (not (fp.isNaN (f X))))
(assert (not (fp.isInfinite (f X))))
(define-fun tiny () W ((_ to_fp 11 53) RNE (f #x00000001)))
(assert (not (and (fp.leq (wide (f (nd X))) (fp.sub RTN (wide (f X)) tiny))
                  (fp.geq (wide (f (nu X))) (fp.add RTP (wide (f X)) tiny)))))
(check-sat)
