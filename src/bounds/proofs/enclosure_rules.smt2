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
(assert (not (and sum scale prod quot_hi quot_lo minmax cmp absmax signs chord wbound)))
(check-sat)
