; The rules of the enclosure check (src/tools/proofs/enclosure/check.rs), in real arithmetic:
; how an end (a value <= or >= the exact value it encloses) combines with others, and
; the lemma its pins use. f32 values are reals here; rounding is STEP's part. The
; script asserts that some rule fails: `unsat` proves them all. No prelude: the
; logic is nonlinear real arithmetic.
(set-logic QF_NRA)
(define-fun mn ((a Real) (b Real)) Real (ite (<= a b) a b))
(define-fun mx ((a Real) (b Real)) Real (ite (<= a b) b a))
(define-fun ab ((a Real)) Real (ite (<= 0.0 a) a (- a)))
; -- sums: ends of one side add up to an end of that side; a - b with b upper is lower.
(declare-const a1 Real) (declare-const A1 Real) (declare-const b1 Real) (declare-const B1 Real)
(define-fun sum () Bool
  (and (=> (and (<= a1 A1) (<= b1 B1)) (<= (+ a1 b1) (+ A1 B1)))
       (=> (and (<= a1 A1) (>= b1 B1)) (<= (- a1 b1) (- A1 B1)))))
; -- a product by an exact factor y keeps the side when y >= 0 and flips it when y <= 0.
(declare-const a2 Real) (declare-const A2 Real) (declare-const y2 Real)
(define-fun scale () Bool
  (and (=> (and (<= a2 A2) (>= y2 0.0)) (<= (* a2 y2) (* A2 y2)))
       (=> (and (<= a2 A2) (<= y2 0.0)) (>= (* a2 y2) (* A2 y2)))))
; -- products of two ends: lower ends >= 0, or upper ends of values >= 0.
(declare-const a3 Real) (declare-const A3 Real) (declare-const b3 Real) (declare-const B3 Real)
(define-fun prod () Bool
  (and (=> (and (<= 0.0 a3) (<= a3 A3) (<= 0.0 b3) (<= b3 B3)) (<= (* a3 b3) (* A3 B3)))
       (=> (and (<= 0.0 A3) (<= A3 a3) (<= 0.0 B3) (<= B3 b3)) (>= (* a3 b3) (* A3 B3)))))
; -- quotients: the divisor b and its exact value B of one strict sign. An upper end of
;    A / B: the numerator an upper end when B > 0 (lower when B < 0, or exact), and the
;    divisor a lower end when a >= 0 (upper when a <= 0, or exact). The lower end mirrors.
(declare-const a4 Real) (declare-const A4 Real) (declare-const b4 Real) (declare-const B4 Real)
(define-fun same () Bool (or (and (> b4 0.0) (> B4 0.0)) (and (< b4 0.0) (< B4 0.0))))
(define-fun quot_hi () Bool
  (=> (and same
           (or (and (>= a4 A4) (> B4 0.0)) (and (<= a4 A4) (< B4 0.0)) (= a4 A4))
           (or (and (>= a4 0.0) (<= b4 B4)) (and (<= a4 0.0) (>= b4 B4)) (= b4 B4)))
      (>= (/ a4 b4) (/ A4 B4))))
(define-fun quot_lo () Bool
  (=> (and same
           (or (and (<= a4 A4) (> B4 0.0)) (and (>= a4 A4) (< B4 0.0)) (= a4 A4))
           (or (and (>= a4 0.0) (>= b4 B4)) (and (<= a4 0.0) (<= b4 B4)) (= b4 B4)))
      (<= (/ a4 b4) (/ A4 B4))))
; -- min and max of ends of one side are ends of that side; and a min whose exact
;    values each have a lower end among its operands is a lower end of their min, the
;    other operands (with those exact values) whatever they are (here b5 beside a5 <= A5).
(declare-const a5 Real) (declare-const A5 Real) (declare-const b5 Real) (declare-const B5 Real)
(declare-const c5 Real)
(define-fun minmax () Bool
  (and (=> (and (<= a5 A5) (<= b5 B5)) (and (<= (mn a5 b5) (mn A5 B5)) (<= (mx a5 b5) (mx A5 B5))))
       (=> (and (<= a5 A5) (<= c5 B5)) (<= (mn (mn a5 b5) c5) (mn A5 B5)))
       (=> (and (>= a5 A5) (>= c5 B5)) (>= (mx (mx a5 b5) c5) (mx A5 B5)))))
; -- a comparison of an upper end below a lower end holds for the exact values: a >= A,
;    b <= B and a < b give A < B (<= likewise); the other way round under the reverse sides.
(declare-const a10 Real) (declare-const A10 Real) (declare-const b10 Real) (declare-const B10 Real)
(define-fun cmp () Bool
  (and (=> (and (>= a10 A10) (<= b10 B10) (< a10 b10)) (< A10 B10))
       (=> (and (>= a10 A10) (<= b10 B10) (<= a10 b10)) (<= A10 B10))
       (=> (and (<= a10 A10) (>= b10 B10) (< A10 B10)) (< a10 b10))))
; -- the two ends of one interval: max(|lo|, |hi|) >= |x|.
(declare-const l6 Real) (declare-const x6 Real) (declare-const h6 Real)
(define-fun absmax () Bool (=> (and (<= l6 x6) (<= x6 h6)) (<= (ab x6) (mx (ab l6) (ab h6)))))
; -- signs: a lower end > 0 (>= 0) has an exact value > 0 (>= 0); an upper end mirrors.
(declare-const a7 Real) (declare-const A7 Real)
(define-fun signs () Bool
  (and (=> (and (<= a7 A7) (> a7 0.0)) (> A7 0.0)) (=> (and (<= a7 A7) (>= a7 0.0)) (>= A7 0.0))
       (=> (and (>= a7 A7) (< a7 0.0)) (< A7 0.0)) (=> (and (>= a7 A7) (<= a7 0.0)) (<= A7 0.0))
       ; a lower end 0 of a value known <= 0 (an upper end 0 of one >= 0): the value is 0
       (=> (and (<= a7 A7) (= a7 0.0) (<= A7 0.0)) (= A7 0.0))
       (=> (and (>= a7 A7) (= a7 0.0) (>= A7 0.0)) (= A7 0.0))))
; -- lemma "a chord through lower ends keeps every t the exact chord keeps" (la2011's
;    time bound): where the exact chord is <= 0, the chord through lower ends is too.
(declare-const l0 Real) (declare-const l1 Real) (declare-const L0 Real) (declare-const L1 Real)
(declare-const t8 Real)
(define-fun chord () Bool
  (=> (and (<= l0 L0) (<= l1 L1) (<= 0.0 t8) (<= t8 1.0)
           (<= (+ (* (- 1.0 t8) L0) (* t8 L1)) 0.0))
      (<= (+ (* (- 1.0 t8) l0) (* t8 l1)) 0.0)))
; -- lemma "w m <= E bounds w by e_hi / m_lo for every m >= m_lo, E <= e_hi"
;    (nilsson2012-depth's w bound from a plane): for w > 0, m >= m_lo, E <= e_hi and
;    w m <= E: w <= e_hi / m_lo when m_lo > 0, w >= e_hi / m_lo when m_lo < 0 > e_hi.
(declare-const w9 Real) (declare-const m9 Real) (declare-const ml9 Real)
(declare-const E9 Real) (declare-const eh9 Real)
(define-fun wbound () Bool
  (=> (and (> w9 0.0) (>= m9 ml9) (<= E9 eh9) (<= (* w9 m9) E9))
      (and (=> (> ml9 0.0) (<= w9 (/ eh9 ml9)))
           (=> (and (< ml9 0.0) (< eh9 0.0)) (>= w9 (/ eh9 ml9))))))
; -- the corner rule: A in [a0, a1] and B in [b0, b1] put A B between the least and the
;    greatest of the four end products, and A / B (b0 > 0 or b1 < 0) between the least
;    and the greatest of the four end quotients.
(declare-const a11 Real) (declare-const a12 Real) (declare-const A11 Real)
(declare-const b11 Real) (declare-const b12 Real) (declare-const B11 Real)
(define-fun in11 () Bool (and (<= a11 A11) (<= A11 a12) (<= b11 B11) (<= B11 b12)))
(define-fun corners () Bool
  (=> in11
      (and (<= (mn (mn (* a11 b11) (* a11 b12)) (mn (* a12 b11) (* a12 b12))) (* A11 B11))
           (>= (mx (mx (* a11 b11) (* a11 b12)) (mx (* a12 b11) (* a12 b12))) (* A11 B11))
           (=> (or (> b11 0.0) (< b12 0.0))
               (and (<= (mn (mn (/ a11 b11) (/ a11 b12)) (mn (/ a12 b11) (/ a12 b12))) (/ A11 B11))
                    (>= (mx (mx (/ a11 b11) (/ a11 b12)) (mx (/ a12 b11) (/ a12 b12))) (/ A11 B11)))))))
; -- lemma "mam2012-safe corners": the bilinear patch through corner values at or below
;    the exact ones is at or below the exact patch at every (s, t) of the unit square.
(declare-const l00 Real) (declare-const l10 Real) (declare-const l01 Real) (declare-const l11 Real)
(declare-const L00 Real) (declare-const L10 Real) (declare-const L01 Real) (declare-const L11 Real)
(declare-const s12 Real) (declare-const t12 Real)
(define-fun bilerp ((p00 Real) (p10 Real) (p01 Real) (p11 Real)) Real
  (+ (* (- 1.0 s12) (- 1.0 t12) p00) (* s12 (- 1.0 t12) p10) (* (- 1.0 s12) t12 p01) (* s12 t12 p11)))
(define-fun mcorners () Bool
  (=> (and (<= l00 L00) (<= l10 L10) (<= l01 L01) (<= l11 L11)
           (<= 0.0 s12) (<= s12 1.0) (<= 0.0 t12) (<= t12 1.0))
      (<= (bilerp l00 l10 l01 l11) (bilerp L00 L10 L01 L11))))
; -- lemmas "mam2012-safe domain" and "mam2012-safe columns": a covered column x lies in
;    the exact extent [E0, E1]; so xa <= E0 <= x <= E1 <= xb, and a column of the tile
;    [t0, t1] lies in [x0, x1] for x0 <= max(t0, E0), x1 >= min(t1, E1).
(declare-const x13 Real) (declare-const E0 Real) (declare-const E1 Real)
(declare-const xa13 Real) (declare-const xb13 Real) (declare-const t0 Real) (declare-const t1 Real)
(declare-const x0 Real) (declare-const x1 Real)
(define-fun mcolumns () Bool
  (=> (and (<= E0 x13) (<= x13 E1))
      (and (=> (and (<= xa13 E0) (>= xb13 E1)) (and (<= xa13 x13) (<= x13 xb13)))
           (=> (and (<= t0 x13) (<= x13 t1) (<= x0 (mx t0 E0)) (>= x1 (mn t1 E1)))
               (and (<= x0 x13) (<= x13 x1))))))
; -- lemma "mam2012-safe patch from either corner": the affine patch through (d0, p0),
;    (d1, p1) read from either corner is one value; with one column (slope 0) both
;    corners are p0.
(declare-const d0 Real) (declare-const d1 Real) (declare-const p0 Real) (declare-const p1 Real)
(declare-const x14 Real)
(define-fun msame () Bool
  (and (=> (> d1 d0)
           (= (+ p0 (* (- x14 d0) (/ (- p1 p0) (- d1 d0)))) (+ p1 (* (- x14 d1) (/ (- p1 p0) (- d1 d0))))))
       (= (+ p0 (* (- x14 d0) 0.0)) (+ p0 (* (- x14 d1) 0.0)))))
; -- lemma "mam2012-safe lines": the line b + a t with b = l0, a = l1 - l0 through lower
;    ends l0 <= L0, l1 <= L1 is at or below the exact line for t in [0, 1].
(declare-const m0 Real) (declare-const m1 Real) (declare-const M0 Real) (declare-const M1 Real)
(declare-const t15 Real)
(define-fun mline () Bool
  (=> (and (<= m0 M0) (<= m1 M1) (<= 0.0 t15) (<= t15 1.0))
      (<= (+ (* (- m1 m0) t15) m0) (+ (* (- 1.0 t15) M0) (* t15 M1)))))
; -- signs of sums and products: two values >= 0 add up to a value >= 0 (<= 0 likewise),
;    and a product of two values of known signs has their product's sign (the rounding
;    keeps it: MONO); so an end moved outward by such an amount stays beyond it.
(declare-const x16 Real) (declare-const y16 Real) (declare-const b16 Real)
(define-fun ksigns () Bool
  (and (=> (and (>= x16 0.0) (>= y16 0.0)) (and (>= (+ x16 y16) 0.0) (>= (* x16 y16) 0.0)))
       (=> (and (<= x16 0.0) (<= y16 0.0)) (and (<= (+ x16 y16) 0.0) (>= (* x16 y16) 0.0)))
       (=> (and (>= x16 0.0) (<= y16 0.0)) (<= (* x16 y16) 0.0))
       (=> (>= x16 0.0) (and (>= (+ b16 x16) b16) (<= (- b16 x16) b16)))))
; -- lemma "wu2013-safe lens range": a lens value of the exact range [L0, L1] lies in
;    [l0, l1] for l0 <= L0, L1 <= l1 (so in the rectangle stage 2 reads at its corners).
(declare-const l17 Real) (declare-const L017 Real) (declare-const L117 Real)
(declare-const l017 Real) (declare-const l117 Real)
(define-fun wlens () Bool
  (=> (and (<= L017 l17) (<= l17 L117) (<= l017 L017) (<= L117 l117)) (and (<= l017 l17) (<= l17 l117))))
; -- lemma "wu2013-safe lines": an intercept b >= e_left + a and >= e_right - a, with
;    e_left >= EL and e_right >= ER, puts the line a l + b at or above the exact line
;    through (-1, EL), (1, ER) for every l in [-1, 1], whatever a is.
(declare-const a18 Real) (declare-const b18 Real) (declare-const el18 Real) (declare-const er18 Real)
(declare-const EL18 Real) (declare-const ER18 Real) (declare-const l18 Real)
(define-fun wline () Bool
  (=> (and (>= b18 (+ el18 a18)) (>= b18 (- er18 a18)) (>= el18 EL18) (>= er18 ER18)
           (<= -1.0 l18) (<= l18 1.0))
      (>= (+ (* a18 l18) b18) (+ (* (/ (- 1.0 l18) 2.0) EL18) (* (/ (+ 1.0 l18) 2.0) ER18)))))
; -- lemma "lb2011-safe corners": the patch P + Q l + t (R + S l) with P = (g00 + g10) / 2,
;    Q = (g10 - g00) / 2, R = (g01 + g11) / 2 - P, S = (g11 - g01) / 2 - Q through corner
;    values g_ij at or above the exact ones G_ij is at or above the bilinear interpolant
;    of the G_ij at (s, t), s = (l + 1) / 2, for |l| <= 1 and t in [0, 1].
(declare-const g00 Real) (declare-const g10 Real) (declare-const g01 Real) (declare-const g11 Real)
(declare-const G00 Real) (declare-const G10 Real) (declare-const G01 Real) (declare-const G11 Real)
(declare-const l19 Real) (declare-const t19 Real)
(define-fun lpatch () Real
  (let ((p (/ (+ g00 g10) 2.0)) (q (/ (- g10 g00) 2.0)))
    (let ((r (- (/ (+ g01 g11) 2.0) p)) (s (- (/ (- g11 g01) 2.0) q)))
      (+ p (* q l19) (* t19 (+ r (* s l19)))))))
(define-fun lcorners () Bool
  (=> (and (>= g00 G00) (>= g10 G10) (>= g01 G01) (>= g11 G11)
           (<= -1.0 l19) (<= l19 1.0) (<= 0.0 t19) (<= t19 1.0))
      (let ((s19 (/ (+ l19 1.0) 2.0)))
        (>= lpatch (+ (* (- 1.0 s19) (- 1.0 t19) G00) (* s19 (- 1.0 t19) G10)
                      (* (- 1.0 s19) t19 G01) (* s19 t19 G11))))))
; -- a fused multiply-add of an end by an exact factor y of known sign plus an end: the
;    product is not rounded, so `scale` and `sum` compose: a y + c <= A y + C for a <= A,
;    y >= 0, c <= C (flipped for y <= 0).
(declare-const a20 Real) (declare-const A20 Real) (declare-const y20 Real)
(declare-const c20 Real) (declare-const C20 Real)
(define-fun fmarule () Bool
  (and (=> (and (<= a20 A20) (>= y20 0.0) (<= c20 C20)) (<= (+ (* a20 y20) c20) (+ (* A20 y20) C20)))
       (=> (and (<= a20 A20) (<= y20 0.0) (>= c20 C20)) (>= (+ (* a20 y20) c20) (+ (* A20 y20) C20)))))
(assert (not (and sum scale prod quot_hi quot_lo minmax cmp absmax signs chord wbound
                 corners mcorners mcolumns msame mline ksigns wlens wline lcorners fmarule)))
(check-sat)
