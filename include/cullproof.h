/*
 * cullproof.h: the C interface of a culling bound that cullproof can gate.
 *
 * A shared library (.so) exports one function, `cullproof_method`, returning a pointer
 * to a `cp_method` that lives as long as the library. cullproof loads it with
 * `cullproof check --plugin path/to/libmybound.so --method my-bound` (and the same
 * `--plugin` for search, replay, explain and tightness).
 *
 * The model (docs/model.md in the cullproof repository): a triangle has three vertices
 * in clip space at shutter open (q) and close (r), each moving linearly in t in [0, 1];
 * a circle of confusion per vertex at both ends (c0, c1, in clip-space x units); the
 * lens aspect k (y shear = k * CoC). A sample (x, y, u, v, t) sees vertex i at
 *   x'_i = x_i(t) + u c_i(t),  y'_i = y_i(t) + k v c_i(t),  w_i(t)
 * and is covered when (x, y) lies strictly inside the projected triangle.
 *
 * The contract of a tile test: for a triangle and a tile [x0, x1] x [y0, y1] the bound
 * answers CP_EMPTY (no covered sample has (x, y) in the tile) or CP_BOUNDS with
 * intervals u^, v^ (within [-1, 1]), t^ (within [0, 1]), an optional depth interval z^
 * and optional per-sample constraints g_m; a sample is culled when some g_m(s) < 0.
 * The bound is conservative iff every covered sample with (x, y) in the tile has u in
 * u^, v in v^, t in t^, its hit depth in z^ and every g_m(s) >= 0.
 *
 * Threads: cullproof calls `setup` and `tile` from several threads at once, each with
 * its own triangle; a state returned by `setup` is only read by `tile` (several tiles
 * of one triangle may be asked concurrently), so it must not be written after setup.
 * A tile state (constraints) is read by `eval` / `eval_box` and freed once.
 *
 * Limits: an answer beyond a cap below (CP_MAX_*) stops the run with an error naming
 * the library, the call and the value (exit code 2); it is checked before cullproof
 * allocates anything for it. Every call (setup, tile, eval, eval_box, ...) must return
 * within `--plugin-timeout` seconds (default 30): a call that has not stops the run
 * with an error naming the library and the call, exit code 2 (the call cannot be
 * interrupted, so the process ends).
 *
 * Contract breaches that have a fail-safe reading are judged as given and counted:
 * a NaN interval end (culls everything), an infinite end of u^, v^ or t^, lo > hi
 * (culls everything), a tile answer that is neither CP_EMPTY nor CP_BOUNDS (taken as
 * CP_EMPTY), constraints without `eval` (ignored), an eval_box enclosure with a NaN end
 * or lo > hi (taken as the whole line). At the end of a run cullproof prints one line
 * per library with its count by kind, and `check --json` lists them
 * (`contract_breaches`).
 *
 * Versioning: `abi_version` must equal CULLPROOF_ABI_VERSION; cullproof refuses a
 * library built against another version, naming both. New fields are only ever
 * appended, with a new version.
 */
#ifndef CULLPROOF_H
#define CULLPROOF_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CULLPROOF_ABI_VERSION 1u

/* Outputs a bound claims to give (cp_method.outputs): reports list them. */
#define CP_OUT_TILE_REJECT 1u /* may answer CP_EMPTY */
#define CP_OUT_LENS 2u        /* narrows u^ / v^ */
#define CP_OUT_TIME 4u        /* narrows t^ */
#define CP_OUT_DEPTH 8u       /* gives z^ */
#define CP_OUT_PER_SAMPLE 16u /* gives per-sample constraints */

/* Answers of cp_method.tile. */
#define CP_EMPTY 0
#define CP_BOUNDS 1

/* Caps (see "Limits" above). */
#define CP_MAX_CONSTRAINTS 4096u /* cp_bounds.n_constraints of one answer */
#define CP_MAX_TEXT 1024u        /* bytes before the NUL: source, a disabled reason, a constraint name */
#define CP_MAX_REASONS 256u      /* distinct `disabled` strings (by address) of one library */

/* One triangle (all f32, exactly as cullproof's model holds it). q[i] and r[i] are
 * (x, y, z, w) of vertex i at t = 0 and t = 1. */
typedef struct cp_triangle {
    float q[3][4];
    float r[3][4];
    float c0[3];
    float c1[3];
    float k;
} cp_triangle;

/* A screen tile [x0, x1] x [y0, y1] in pixels. */
typedef struct cp_tile {
    float x0, y0, x1, y1;
} cp_tile;

/* A sample. */
typedef struct cp_sample {
    float x, y, u, v, t;
} cp_sample;

/* A closed interval of doubles (lo <= hi, neither NaN; -INFINITY / INFINITY allowed). */
typedef struct cp_interval {
    double lo, hi;
} cp_interval;

/* A box of samples, one interval per coordinate. */
typedef struct cp_sample_box {
    cp_interval x, y, u, v, t;
} cp_sample_box;

/* The non-empty answer of a tile test. cullproof fills it with the full domain
 * (u, v in [-1, 1], t in [0, 1], no depth, no constraints) before the call. Every
 * interval has lo <= hi and no NaN end; the ends of u, v and t are finite, those of z
 * may be infinite. */
typedef struct cp_bounds {
    float u[2];
    float v[2];
    float t[2];
    int32_t has_z; /* nonzero: z[] holds the depth interval */
    float z[2];
    /* Per-sample constraints valid for this tile: their number (at most
     * CP_MAX_CONSTRAINTS), and an opaque tile state handed back to eval / eval_box /
     * constraint_name / free_tile (NULL when there are none). */
    uint32_t n_constraints;
    void *tile_state;
} cp_bounds;

typedef struct cp_method {
    uint32_t abi_version; /* CULLPROOF_ABI_VERSION */
    const char *id;       /* the method id, e.g. "my-bound": letters, digits, '-', '_', '.' */
    const char *source;   /* one line: what it is, where it comes from (<= CP_MAX_TEXT bytes) */
    uint32_t outputs;     /* CP_OUT_* flags */

    /* Per-triangle setup. Returns the state handed to `tile` (may be NULL when the
     * bound needs none). *disabled may be set to a static string saying why the
     * bound gives no information for this triangle (then every tile should get the
     * full bounds); leave it NULL otherwise. At most CP_MAX_REASONS distinct such
     * strings, each at most CP_MAX_TEXT bytes. */
    void *(*setup)(const cp_triangle *tri, const char **disabled);

    /* The tile test: CP_EMPTY or CP_BOUNDS (then *out holds the answer). */
    int32_t (*tile)(const void *state, const cp_tile *tile, cp_bounds *out);

    /* Per-sample constraint m of a tile: the value hardware computes, in f32; the
     * sample is culled when it is < 0. Required when a tile answers constraints. */
    float (*eval)(const void *tile_state, uint32_t m, const cp_sample *s);

    /* An enclosure of every value `eval` can return for a sample in the box, f32
     * rounding included. Optional (NULL): then cullproof cannot certify the
     * constraint, and a case whose tile has constraints is at best unproven. Return
     * nonzero on success. */
    int32_t (*eval_box)(const void *tile_state, uint32_t m, const cp_sample_box *b, cp_interval *out);

    /* A short label for constraint m (optional, NULL: "constraint m"). The string
     * must live as long as the tile state (at most CP_MAX_TEXT bytes). */
    const char *(*constraint_name)(const void *tile_state, uint32_t m);

    /* Free a tile state (optional; called once per non-NULL tile_state). */
    void (*free_tile)(void *tile_state);

    /* Free a triangle state (optional; called once per setup). */
    void (*free_state)(void *state);
} cp_method;

/* The one exported entry point. */
const cp_method *cullproof_method(void);

#ifdef __cplusplus
}
#endif

#endif /* CULLPROOF_H */
