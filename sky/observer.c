/*
 * Where and when: the observer, the time slider as local apparent solar
 * time, and the public astronomy queries. The astronomy itself is astro.c;
 * the star catalogue is catalog.c.
 */
#include "catalog.h"
#include "observer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (SKY_PI / 180.0)

sky_observer sky_default_observer(void)
{
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.julian_day_utc = sky_jd_from_calendar(2026, 3, 20, 12, 0, 0.0);
    o.latitude_deg = 40.0;
    o.time_from_params = 1;
    return o;
}

/* The calendar arithmetic holds in longs for a million years either way
 * of year 0 (Julian day 1721059.5 is 0000-01-01), far beyond any
 * ephemeris: the public functions take only that. */
#define SKY_CALENDAR_YEARS 1000000
#define SKY_CALENDAR_JD_YEAR0 1721059.5
#define SKY_CALENDAR_JD_SPAN ((SKY_CALENDAR_YEARS + 1) * 365.2425)

double sky_julian_day(int year, int month, int day, int hour, int minute, double second)
{
    if (year < -SKY_CALENDAR_YEARS || year > SKY_CALENDAR_YEARS || month < 1 || month > 12 || day < 1 || day > 31 ||
        hour < 0 || hour > 24 || minute < 0 || minute > 60 || !(second >= 0.0 && second <= 61.0))
        return NAN;
    return sky_jd_from_calendar(year, month, day, hour, minute, second);
}

sky_result sky_calendar(double jd, int *year, int *month, int *day, double *day_fraction)
{
    int y = 0, m = 0, d = 0;
    double f = 0.0;
    int ok = isfinite(jd) && fabs(jd - SKY_CALENDAR_JD_YEAR0) <= SKY_CALENDAR_JD_SPAN;
    if (ok) sky_calendar_from_jd(jd, &y, &m, &d, &f);
    if (year) *year = y;
    if (month) *month = m;
    if (day) *day = d;
    if (day_fraction) *day_fraction = f;
    return ok ? SKY_OK : SKY_ERR_INVALID_ARGUMENT;
}

int sky_observer_check(const sky_observer *o, char *err, size_t err_len)
{
    /* the calendar bounds themselves: a Julian-year estimate of the year
     * drifts by a month from the Gregorian calendar 4000 years out */
    double first = sky_jd_from_calendar(SKY_ASTRO_YEAR_MIN, 1, 1, 0, 0, 0.0),
           after_last = sky_jd_from_calendar(SKY_ASTRO_YEAR_MAX + 1, 1, 1, 0, 0, 0.0);
    if (!isfinite(o->julian_day_utc) || o->julian_day_utc < first || o->julian_day_utc >= after_last)
        sky_format(err, err_len, "observer: the date (JD %g) is outside the years %d..%d", o->julian_day_utc,
                   SKY_ASTRO_YEAR_MIN, SKY_ASTRO_YEAR_MAX);
    else if (!isfinite(o->latitude_deg) || fabs(o->latitude_deg) > 90.0)
        sky_format(err, err_len, "observer: latitude %g is outside -90..90", o->latitude_deg);
    else if (!isfinite(o->longitude_deg) || fabs(o->longitude_deg) > 180.0)
        sky_format(err, err_len, "observer: longitude %g is outside -180..180", o->longitude_deg);
    else if (!isfinite(o->altitude_m) || o->altitude_m < -500.0 || o->altitude_m > 100000.0)
        sky_format(err, err_len, "observer: altitude %g m is outside -500..100000", o->altitude_m);
    else
        return 0;
    return -1;
}

/* The instant the observer and the time slider describe. With the slider,
 * local apparent solar time `time_of_day` on the observer's local (mean
 * solar) date: start from mean solar time, then correct once by the
 * measured difference (the equation of time, at most 17 minutes, changes
 * by seconds a day, so one correction is exact to well under a second). */
static int astro_at(double jd, const sky_astro_observer *ao, sky_astro_cache *cache, sky_astro *a, char *err,
                    size_t err_len)
{
    return sky_astro_compute_cached(jd, isfinite(jd) ? sky_delta_t(jd) : 0.0, ao, cache, a, err, err_len);
}

int sky_observer_astro(const sky_observer *o, double time_of_day, sky_astro_cache *cache, sky_astro *a, char *err,
                       size_t err_len)
{
    /* without one, a cache of this call's own: the two instants below,
     * at most the equation of time apart, share their nodes */
    sky_astro_cache own = {0};
    if (!cache) cache = &own;
    sky_astro_observer ao = {o->latitude_deg * DEG, o->longitude_deg * DEG, o->altitude_m};
    if (!o->time_from_params) return astro_at(o->julian_day_utc, &ao, cache, a, err, err_len);
    double lon_days = o->longitude_deg / 360.0;
    double local_midnight = floor(o->julian_day_utc + lon_days + 0.5) - 0.5;
    double tod = sky_clampd(time_of_day, 0.0, 1.0);
    double jd = local_midnight + tod - lon_days;
    if (astro_at(jd, &ao, cache, a, err, err_len)) return -1;
    /* apparent solar time now: the sun's hour angle + 12 h */
    double solar = sky_wrap((a->last - a->sun.ra) / (2.0 * SKY_PI) + 0.5, 1.0);
    double correction = sky_wrap(tod - solar + 0.5, 1.0) - 0.5;
    return astro_at(jd + correction, &ao, cache, a, err, err_len);
}

static void body_out(const sky_astro_body *b, sky_body_place *p)
{
    p->alt_deg = b->alt / DEG;
    p->alt_geometric_deg = b->alt_geometric / DEG;
    p->az_deg = b->az / DEG;
    p->ra_deg = b->ra / DEG;
    p->dec_deg = b->dec / DEG;
    p->distance_km = b->distance_km;
}

void sky_astronomy_from_astro(const sky_astro *a, sky_astronomy *o)
{
    memset(o, 0, sizeof *o);
    o->julian_day_ut = a->jd_ut;
    o->delta_t_s = a->delta_t;
    o->lmst_deg = a->lmst / DEG;
    body_out(&a->sun, &o->sun);
    body_out(&a->moon, &o->moon);
    o->moon_illuminated_fraction = a->moon_illuminated;
    o->moon_phase_angle_deg = a->moon_phase_angle / DEG;
    o->moon_bright_limb_deg = a->moon_bright_limb / DEG;
    o->moon_libration_lat_deg = a->moon_libration_lat / DEG;
    o->moon_libration_lon_deg = a->moon_libration_lon / DEG;
    o->moon_axis_angle_deg = a->moon_axis_angle / DEG;
    o->moon_parallactic_deg = a->moon_parallactic / DEG;
    o->umbral_magnitude = a->umbral_magnitude;
    o->penumbral_magnitude = a->penumbral_magnitude;
    o->solar_obscuration = a->solar_obscuration;
    o->solar_magnitude = a->solar_magnitude;
    o->solar_flux_fraction = a->solar_flux_fraction;
    o->star_visibility = a->star_visibility;
    o->moon_visibility = a->moon_visibility;
}

const char *sky_planet_name(sky_planet planet)
{
    const char *name = sky_astro_planet_name((int)planet);
    return name ? name : "unknown";
}

_Static_assert((int)SKY_PLANET_COUNT == SKY_ASTRO_PLANETS, "the public planets are astro.c's");

void sky_planets_out(const sky_astro_planet places[SKY_ASTRO_PLANETS], sky_astronomy *out)
{
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        const sky_astro_planet *pl = &places[p];
        sky_planet_place *o = &out->planets[p];
        body_out(&pl->body, &o->place);
        o->distance_au = pl->distance_au;
        o->vmag = pl->vmag;
        o->illuminated_fraction = pl->illuminated;
        o->phase_angle_deg = pl->phase_angle / DEG;
        o->diameter_arcsec = pl->diameter / DEG * 3600.0;
    }
}

void sky_planets_fill(const sky_astro *a, sky_astronomy *out)
{
    sky_astro_planet places[SKY_ASTRO_PLANETS];
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        sky_planet_state st;
        sky_planet_state_at(p, a->jd_tt, &st);
        sky_astro_planet_place(a, p, &st, &places[p]);
    }
    sky_planets_out(places, out);
}

sky_result sky_compute_astronomy(const sky_observer *obs, float time_of_day, const int *hip, int count,
                                 sky_star_place *stars, sky_astronomy *out, char *err, size_t err_len)
{
    if (err && err_len) err[0] = '\0';
    if (!obs || !out || count < 0 || (count > 0 && (!hip || !stars))) {
        sky_format(err, err_len, "sky_compute_astronomy: NULL observer or output, or a bad star list");
        return SKY_ERR_INVALID_ARGUMENT;
    }
    if (isnan(time_of_day)) {
        sky_format(err, err_len, "sky_compute_astronomy: time_of_day is NaN");
        return SKY_ERR_INVALID_ARGUMENT;
    }
    if (sky_observer_check(obs, err, err_len)) return SKY_ERR_INVALID_ARGUMENT;
    sky_astro a;
    if (sky_observer_astro(obs, time_of_day, NULL, &a, err, err_len)) return SKY_ERR_INVALID_ARGUMENT;
    sky_astronomy_from_astro(&a, out);
    sky_planets_fill(&a, out);
    if (count == 0) return SKY_OK;
    sky_catalog cat;
    if (sky_catalog_load(&cat, err, err_len)) return SKY_ERR_ASSET;
    for (int i = 0; i < count; i++) {
        sky_star_place *p = &stars[i];
        memset(p, 0, sizeof *p);
        p->hip = hip[i];
        const sky_star *st = sky_catalog_find(&cat, hip[i]);
        if (!st) continue;
        double alt, alt_geo, az, dir[3];
        sky_astro_star(&a, st, &alt, &alt_geo, &az, dir);
        p->found = 1;
        p->alt_deg = alt / DEG;
        p->alt_geometric_deg = alt_geo / DEG;
        p->az_deg = az / DEG;
        p->vmag = st->vmag;
        p->bv = st->bv;
    }
    sky_catalog_free(&cat);
    return SKY_OK;
}

/* (sky/astro.c has a DEG of its own: in the amalgamation's one
 * translation unit each file's ends with it) */
#undef DEG
