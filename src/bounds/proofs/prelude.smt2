; Shared definitions of the rounding lemmas (included before each lemma by
; src/bounds/proofs/mod.rs; pure floating-point and bit-vector theory, no reals).
; F: IEEE binary32 as Rust's f32. W: binary64, holding every f32 value, every
; midpoint between neighbouring f32 values and the overflow threshold MAX + ulp/2.
(set-logic QF_BVFP)
(define-sort F () (_ FloatingPoint 8 24))
(define-sort W () (_ FloatingPoint 11 53))
(define-fun f ((b (_ BitVec 32))) F ((_ to_fp 8 24) b))
(define-fun wide ((x F)) W ((_ to_fp 11 53) RNE x))
(define-fun rn ((z W)) F ((_ to_fp 8 24) RNE z))
; "r is a finite rounding to nearest of z": both f32 neighbours of z are finite and r is
; the one below (above) z, no farther from z than the one above (below). The
; distances are rounded so that every true nearest neighbour qualifies (a superset:
; a lemma proven for all of them holds for the true ones); this form also covers the
; midpoints between two f32 values with either neighbour, which is what extends a
; lemma from W to every real (docs/proofs.md, "From W to the reals").
(define-fun near_lo ((z W) (r F)) Bool
  (let ((lo ((_ to_fp 8 24) RTN z)) (hi ((_ to_fp 8 24) RTP z)))
    (and (= r lo) (not (fp.isInfinite lo)) (not (fp.isInfinite hi))
         (fp.leq (fp.sub RTN z (wide lo)) (fp.sub RTP (wide hi) z)))))
(define-fun near_hi ((z W) (r F)) Bool
  (let ((lo ((_ to_fp 8 24) RTN z)) (hi ((_ to_fp 8 24) RTP z)))
    (and (= r hi) (not (fp.isInfinite lo)) (not (fp.isInfinite hi))
         (fp.leq (fp.sub RTN (wide hi) z) (fp.sub RTP z (wide lo))))))
; At the overflow threshold T = MAX + ulp/2 (= MAX + 2^103) the two nearest values
; are MAX and 2^128 (the grid continued past MAX): RN rounds T itself to +inf, but a
; real just below T rounds to MAX, and the step from W to the reals needs the lemma
; for the pair (T, MAX). near_top admits r = +-MAX for every z from +-MAX out to +-T.
(define-fun thr () W (fp.add RNE (wide (f #x7f7fffff)) (wide (f #x73000000))))
(define-fun near_top ((z W) (r F)) Bool
  (or (and (= r (f #x7f7fffff)) (fp.leq (wide r) z) (fp.leq z thr))
      (and (= r (f #xff7fffff)) (fp.leq (fp.neg thr) z) (fp.leq z (wide r)))))
(define-fun near ((z W) (r F)) Bool (or (near_lo z r) (near_hi z r) (near_top z r)))
; next_down / next_up on the bits of a non-NaN f32, as Rust's f32::next_down /
; f32::next_up: +-0 go to -+2^-149, -inf and +inf stay, otherwise one unit of the
; magnitude's bits towards (next_up: away from) -inf.
(define-fun nd ((b (_ BitVec 32))) (_ BitVec 32)
  (ite (= ((_ extract 30 0) b) #b0000000000000000000000000000000) #x80000001
  (ite (= b #xff800000) b
  (ite (= ((_ extract 31 31) b) #b0) (bvsub b #x00000001) (bvadd b #x00000001)))))
(define-fun nu ((b (_ BitVec 32))) (_ BitVec 32)
  (ite (= ((_ extract 30 0) b) #b0000000000000000000000000000000) #x00000001
  (ite (= b #x7f800000) b
  (ite (= ((_ extract 31 31) b) #b0) (bvadd b #x00000001) (bvsub b #x00000001)))))
; The neighbours as values of W, with the f32 grid continued past MAX: the value after
; MAX is 2^128 (and before -MAX, -2^128) instead of an infinity.
(define-fun two128 () W (fp.mul RNE (wide (f #x7f000000)) ((_ to_fp 11 53) RNE 2.0)))
(define-fun wnd ((b (_ BitVec 32))) W (ite (= b #xff7fffff) (fp.neg two128) (wide (f (nd b)))))
(define-fun wnu ((b (_ BitVec 32))) W (ite (= b #x7f7fffff) two128 (wide (f (nu b)))))
