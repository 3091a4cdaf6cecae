#!/usr/bin/env python3
"""A culling bound in Python, gated by cullproof over the process protocol
(docs/protocol.md):

    cullproof check --exec "python3 examples/python/bbox_exec.py" --method py-bbox

The bound: the screen box of the moving, defocused triangle over the lens corners and
the shutter ends, (x +- c) / w and (y +- k c) / w per vertex and end. Python computes
in f64; each corner value is padded outward by 2^-40 of its operands' size (far more
than the two f64 roundings it can err by), so every culled tile is empty. It answers
only tile rejects (an interval-only bound).

With the argument --broken it pulls the box in by 1/8 px: a planted bug the gate
catches. With --constraint it also declares one affine per-sample constraint that
keeps every sample (g = 1 + 0 x + ...), which the gate certifies like a built-in one.
"""
import json
import math
import sys

BROKEN = "--broken" in sys.argv
CONSTRAINT = "--constraint" in sys.argv
PAD = 2.0 ** -40


def box(tri):
    """[x0, x1, y0, y1] or None when a vertex has w <= 0 at a shutter end (unbounded)."""
    ends = [(tri["q"], tri["c0"]), (tri["r"], tri["c1"])]
    out = []
    for axis, scale in ((0, 1.0), (1, tri["k"])):
        lo, hi = math.inf, -math.inf
        for p, c in ends:
            for i in range(3):
                a, w, s = p[i][axis], p[i][3], scale * c[i]
                if not w > 0.0:
                    return None
                for n in (a - s, a + s):
                    q = n / w
                    pad = (abs(n) + abs(s)) / w * PAD + 1e-300
                    lo, hi = min(lo, q - pad), max(hi, q + pad)
        if not (math.isfinite(lo) and math.isfinite(hi)):
            lo, hi = -math.inf, math.inf
        if BROKEN:
            lo, hi = lo + 0.125, hi - 0.125
        out += [lo, hi]
    return out


def answer(req):
    op = req.get("op")
    if op == "hello":
        return {
            "protocol": 1,
            "id": "py-bbox-broken" if BROKEN else ("py-bbox-c" if CONSTRAINT else "py-bbox"),
            "source": "screen box over lens corners and shutter ends, in Python (f64, padded)",
            "outputs": ["tile-reject"] + (["per-sample"] if CONSTRAINT else []),
        }
    if op == "tile":
        b = box(req["tri"])
        x0, y0, x1, y1 = req["tile"]
        if b is not None and (x1 < b[0] or x0 > b[1] or y1 < b[2] or y0 > b[3]):
            return {"n": req["n"], "empty": True}
        a = {"n": req["n"]}
        if CONSTRAINT:
            a["constraints"] = [{"form": "affine", "name": "keep all", "c": [1, 0, 0, 0, 0, 0]}]
        return a
    return {"n": req.get("n"), "error": "unknown op %r" % op}


def main():
    out = sys.stdout
    for line in sys.stdin:
        try:
            a = answer(json.loads(line))
        except Exception as e:  # report, never guess
            a = {"n": None, "error": "%s: %s" % (type(e).__name__, e)}
        out.write(json.dumps(a) + "\n")
        out.flush()


if __name__ == "__main__":
    main()
