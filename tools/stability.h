/*
 * The numerical-stability suite (issue 8): hard cases tried through the
 * public API, each reduced to one row — the property, the worst value the
 * sweep found, the tolerance it is held to. sky-bench --stability prints
 * the table; the test runner asserts every row passes.
 */
#ifndef SKY_STABILITY_H
#define SKY_STABILITY_H

#include "sky.h"

#include <stddef.h>

typedef struct sky_stability_row {
    const char *name;     /* the case                                   */
    const char *property; /* what must hold                             */
    const char *unit;     /* of worst and tolerance                     */
    double worst;         /* the worst value found over the sweep       */
    double tolerance;     /* pass when worst <= tolerance               */
    long samples;         /* evaluations the sweep made                 */
    int pass;
} sky_stability_row;

enum { SKY_STABILITY_MAX_ROWS = 24 };

/* Runs the CPU cases (astronomy) and, when gpu is set, the render cases
 * in fresh OSMesa float contexts. Fills rows, returns how many (or -1
 * when a context cannot be made; err says why). */
int sky_stability_run(int gpu, sky_stability_row rows[SKY_STABILITY_MAX_ROWS], char *err, size_t err_len);
/* The render cases alone, on a fresh float context of profile gl (ES20:
 * an ES 3 context drawing into an RGBA32F target, the one way an ES
 * context shows a NaN). */
int sky_stability_run_render(sky_gl_profile gl, sky_stability_row rows[SKY_STABILITY_MAX_ROWS], char *err,
                             size_t err_len);

/* Resident memory of this process in KiB (Linux /proc), or -1: the soaks'
 * measure (sky-bench --soak, the tests' soak). */
long sky_rss_kib(void);

#endif
