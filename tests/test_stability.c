/*
 * The numerical-stability suite (tools/stability.c, issue 8) as a test:
 * every row must hold its tolerance. The same rows are the table of
 * sky-bench --stability.
 */
#include "test.h"
#include "sky_internal.h"
#include "stability.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Every row passes. */
static void check_rows(const sky_stability_row *rows, int n)
{
    for (int i = 0; i < n; i++) {
        NOTE("%-52s worst %.3g (tolerance %.3g, %ld samples)", rows[i].name, rows[i].worst, rows[i].tolerance,
             rows[i].samples);
        CHECK(rows[i].samples > 0, "%s: the sweep evaluated nothing", rows[i].name);
        CHECK(rows[i].pass && rows[i].worst <= rows[i].tolerance, "%s: %s: worst %g > %g", rows[i].name,
              rows[i].property, rows[i].worst, rows[i].tolerance);
    }
}

SLOW_TEST(stability_suite)
{
    sky_stability_row rows[SKY_STABILITY_MAX_ROWS];
    char err[512];
    int n = sky_stability_run(1, rows, err, sizeof err);
    CHECK(n > 0, "the suite ran: %s", err);
    check_rows(rows, n);
}

/* The render cases through the ES20 profile's GLSL ES 1.00 shaders (an ES
 * 3 context's float target: an 8-bit ES 2.0 one cannot show a NaN). */
SLOW_TEST(stability_suite_es20)
{
#ifdef _WIN32
    SKIP("OpenGL ES contexts come from EGL, on Linux (the Windows runner draws through WGL)");
    return;
#endif
    sky_stability_row rows[SKY_STABILITY_MAX_ROWS];
    char err[512];
    int n = sky_stability_run_render(SKY_GL_ES20, rows, err, sizeof err);
    CHECK(n > 0, "the render cases ran on ES20: %s", err);
    check_rows(rows, n);
}

/* The clocks behind cloud drift, flicker and scintillation wrap before
 * they multiply, so no step overflows them. The frames of the suite do
 * not show a NaN clock (the star shader's max() swallows it on
 * llvmpipe), so the clocks are checked here directly: before the fix,
 * two sky_update(DBL_MAX) left the scintillation clock infinite and the
 * flicker phase NaN. */
TEST(stability_clocks_survive_any_step)
{
    const double steps[] = {0.0, 1e-9, 0.016, 1e9, 1e300, DBL_MAX};
    const double rates[] = {0.0, 2.0 / 255.0, -0.013, 10.0 / 997.0, 1e6};
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++)
        for (size_t j = 0; j < sizeof rates / sizeof rates[0]; j++) {
            double ph = sky_phase_advance(sky_phase_advance(0.25, rates[j], steps[i]), rates[j], steps[i]);
            CHECK(ph >= 0.0 && ph < 1.0, "phase after two steps of %g at rate %g: %g", steps[i], rates[j], ph);
        }
    /* a frame's step is taken exactly: 0.25 + 0.016 * 2/255 */
    double small = sky_phase_advance(0.25, 2.0 / 255.0, 0.016);
    CHECK(fabs(small - (0.25 + 0.016 * 2.0 / 255.0)) < 1e-15, "a short step is exact: %.17g", small);
    /* and across one wrap, a step of 1.5 cycles lands half a cycle on */
    double wrapped = sky_phase_advance(0.25, 0.5, 3.0);
    CHECK(fabs(wrapped - 0.75) < 1e-12, "1.5 cycles from 0.25: %.17g", wrapped);

    fixture f;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_FEATURES_AVAILABLE;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "no fixture");
        return;
    }
    sky_params p = sky_default_params();
    p.speed = 1.0f;
    sky_set_params(f.s, &p);
    CHECK(sky_update(f.s, DBL_MAX) == SKY_OK && sky_update(f.s, DBL_MAX) == SKY_OK, "DBL_MAX is a valid step");
    double scintillation = sky_stars_clock(f.s->layer_state[SKY_LAYER_STARS]);
    double flicker = sky_flicker_clock(f.s->layer_state[SKY_LAYER_FLICKER]);
    const double *offsets = sky_clouds_offsets(f.s->layer_state[SKY_LAYER_CLOUDS]);
    int finite = isfinite(scintillation) && isfinite(flicker);
    for (int l = 0; l < 2 * SKY_CLOUD_LAYERS; l++) finite = finite && isfinite(offsets[l]);
    CHECK(finite, "every clock finite after two DBL_MAX steps (scint %g, flicker %g)", scintillation, flicker);
    fixture_close(&f);
}
