/*
 * A culling bound in C, gated by cullproof through include/cullproof.h:
 * the screen box of a moving, defocused triangle over the whole lens and shutter,
 * each corner value (a +- s) / w padded outward by a bound on its f32 rounding
 * error (the same error analysis as cullproof's built-in bbox-safe), so that every
 * tile it culls is empty.
 *
 * Build:  cc -O2 -ffp-contract=off -shared -fPIC -I include \
 *            -o libc_bbox_safe.so examples/c/bbox_safe.c -lm
 * Gate:   cullproof check --plugin ./libc_bbox_safe.so --method c-bbox-safe
 *
 * Built with -DCULLPROOF_BROKEN it becomes "c-bbox-broken": the box is pulled in by
 * 1/8 px on every side, a planted bug the gate must catch.
 * -ffp-contract=off: no fused multiply-adds, every operation rounded as written.
 */
#include "cullproof.h"
#include <math.h>
#include <stdlib.h>

typedef struct {
    float box[4]; /* x min, x max, y min, y max; NaN on an axis: never culls */
} state;

static float down(float x) { return nextafterf(x, -INFINITY); }
static float up(float x) { return nextafterf(x, INFINITY); }

static void *setup(const cp_triangle *tri, const char **disabled) {
    const float pad_scale = 1.0f / 2097152.0f; /* 2^-21 */
    const float floor_ = 0x1p-120f;            /* covers underflow of k c and n / w */
    const float(*ends[2])[4] = {tri->q, tri->r};
    const float *cocs[2] = {tri->c0, tri->c1};
    for (int e = 0; e < 2; e++)
        for (int i = 0; i < 3; i++)
            if (!(ends[e][i][3] > 0.0f)) { /* w <= 0 or NaN at a shutter end */
                *disabled = "some w_i(t) <= 0 in the shutter: the screen box is unbounded";
                return NULL;
            }
    state *st = malloc(sizeof *st);
    if (!st) return NULL;
    for (int axis = 0; axis < 2; axis++) {
        float scale = axis == 0 ? 1.0f : tri->k;
        float lo = INFINITY, hi = -INFINITY;
        int finite = 1;
        for (int e = 0; e < 2; e++)
            for (int i = 0; i < 3; i++) {
                float a = ends[e][i][axis], w = ends[e][i][3], s = scale * cocs[e][i];
                for (int sign = -1; sign <= 1; sign += 2) {
                    float n = sign < 0 ? a - s : a + s;
                    float q = n / w;
                    float p = ((fabsf(s) + fabsf(n) + floor_) / w) * pad_scale;
                    float l = down(down(down(down(q - p)))), h = up(up(up(up(q + p))));
                    if (!isfinite(l) || !isfinite(h)) finite = 0;
                    if (l < lo) lo = l;
                    if (h > hi) hi = h;
                }
            }
#ifdef CULLPROOF_BROKEN
        lo += 0.125f;
        hi -= 0.125f;
#endif
        st->box[2 * axis] = finite ? lo : NAN;
        st->box[2 * axis + 1] = finite ? hi : NAN;
    }
    return st;
}

static int32_t tile(const void *state_, const cp_tile *t, cp_bounds *out) {
    (void)out; /* full bounds: this bound only rejects tiles */
    const state *st = state_;
    if (!st) return CP_BOUNDS;
    /* Comparisons with NaN are false: an axis with a non-finite box never culls. */
    if (t->x1 < st->box[0] || t->x0 > st->box[1] || t->y1 < st->box[2] || t->y0 > st->box[3]) return CP_EMPTY;
    return CP_BOUNDS;
}

static void free_state(void *s) { free(s); }

static const cp_method method = {
    .abi_version = CULLPROOF_ABI_VERSION,
#ifdef CULLPROOF_BROKEN
    .id = "c-bbox-broken",
    .source = "bbox-safe in C with the box pulled in by 1/8 px (a planted bug)",
#else
    .id = "c-bbox-safe",
    .source = "bbox-safe in C: screen box over lens corners and shutter ends, padded by its f32 error bound",
#endif
    .outputs = CP_OUT_TILE_REJECT,
    .setup = setup,
    .tile = tile,
    .free_state = free_state,
};

const cp_method *cullproof_method(void) { return &method; }
