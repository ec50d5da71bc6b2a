/*
 * The numerical-stability suite (demo/stability.c, issue 8) as a test:
 * every row must hold its tolerance. The same rows are the table of
 * sky-bench --stability.
 */
#include "test.h"
#include "stability.h"

#include <math.h>

void test_stability_suite(void);
void test_stability_date_range_edges(void);

void test_stability_suite(void)
{
    sky_stability_row rows[SKY_STABILITY_MAX_ROWS];
    char err[512];
    int n = sky_stability_run(1, rows, err, sizeof err);
    CHECK(n > 0, "the suite ran: %s", err);
    for (int i = 0; i < n; i++) {
        NOTE("%-52s worst %.3g (tolerance %.3g, %ld samples)", rows[i].name, rows[i].worst, rows[i].tolerance,
             rows[i].samples);
        CHECK(rows[i].samples > 0, "%s: the sweep evaluated nothing", rows[i].name);
        CHECK(rows[i].pass && rows[i].worst <= rows[i].tolerance, "%s: %s: worst %g > %g", rows[i].name,
              rows[i].property, rows[i].worst, rows[i].tolerance);
    }
}

/* The supported range ends on calendar days, not on a Julian-year
 * estimate that drifts a month from the calendar 4000 years out (the
 * suite found the old check admitting late December of -2000). */
void test_stability_date_range_edges(void)
{
    struct {
        int year, month, day, hour;
        int ok;
    } edges[] = {{-1999, 1, 1, 0, 1}, {-2000, 12, 31, 23, 0}, {-2000, 12, 1, 0, 0},
                 {3000, 12, 31, 23, 1}, {3001, 1, 1, 0, 0},   {3001, 1, 20, 0, 0}};
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++) {
        sky_observer o = {sky_julian_day(edges[k].year, edges[k].month, edges[k].day, edges[k].hour, 0, 0.0), 0.0,
                          0.0, 0.0, 0};
        sky_astronomy a;
        char err[256] = "";
        int ok = sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, err, sizeof err) == SKY_OK;
        CHECK(ok == edges[k].ok, "%d-%02d-%02d %02dh: expected %s (%s)", edges[k].year, edges[k].month, edges[k].day,
              edges[k].hour, edges[k].ok ? "accepted" : "an error", err);
        if (ok) CHECK(isfinite(a.sun.alt_deg) && isfinite(a.moon.alt_deg), "finite at the edge");
    }
}
