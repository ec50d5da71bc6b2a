/*
 * Positional astronomy for libsky: time scales, the sun (VSOP87 as
 * truncated by Meeus), the moon (Meeus ch. 47, the full 60 + 60 terms),
 * the planets Mercury to Saturn (VSOP87D truncated by tools/vsopgen.c,
 * Meeus ch. 33; magnitudes of Mallama & Hilton 2018),
 * catalogue stars (proper motion, precession, nutation, aberration),
 * topocentric horizon coordinates with refraction, the moon's phase,
 * libration and orientation, and lunar eclipse magnitudes. Pure C, double
 * precision, no GL. Internal to the library; tests link it directly.
 *
 * Angles are radians unless a name says _deg. Azimuth is measured from
 * north through east. "Apparent" means of date: nutation and aberration
 * applied.
 */
#ifndef SKY_ASTRO_H
#define SKY_ASTRO_H

#include <stddef.h>

/* Supported span of dates: where the Delta T fit is defined. */
#define SKY_ASTRO_YEAR_MIN (-1999)
#define SKY_ASTRO_YEAR_MAX 3000

/* ---- time ------------------------------------------------------------------ */

/* Julian day of a proleptic Gregorian calendar instant (any year). */
double sky_jd_from_calendar(int year, int month, int day, int hour, int minute, double second);
/* The calendar date of a Julian day (proleptic Gregorian). */
void sky_calendar_from_jd(double jd, int *year, int *month, int *day, double *day_fraction);
/* Julian day of Unix seconds. */
double sky_jd_from_unix(double unix_seconds);
/* Delta T = TT - UT in seconds: Espenak & Meeus (2006) polynomials,
 * defined for -1999..+3000 and extrapolated parabolically outside. */
double sky_delta_t(double jd_ut);
/* Greenwich mean sidereal time in radians (Meeus 12.4), UT1 ~ UTC. */
double sky_gmst(double jd_ut);

/* ---- results ------------------------------------------------------------------ */

typedef struct sky_astro_observer {
    double latitude, longitude; /* geodetic, radians; east positive */
    double altitude_m;
} sky_astro_observer;

typedef struct sky_astro_body {
    double ra, dec;            /* geocentric apparent, of date              */
    double distance_km;        /* geocentric                                */
    double topo_distance_km;   /* from the observer                         */
    double alt, alt_geometric; /* topocentric; alt includes refraction     */
    double az;
    double dir[3];             /* horizon frame (+x east, +y up, +z south),
                                  refracted                                 */
    double dir_geometric[3];   /* the same without refraction               */
} sky_astro_body;

typedef struct sky_astro {
    double jd_ut, jd_tt, delta_t;  /* days, days, seconds                    */
    double lmst, last;             /* local mean / apparent sidereal time     */
    double obliquity;              /* true obliquity of date                  */
    double nutation_longitude;
    sky_astro_body sun, moon;
    /* moon */
    double moon_phase_angle;       /* sun-moon-earth angle: 0 full, pi new    */
    double moon_illuminated;       /* fraction of the disc lit, 0..1          */
    double moon_bright_limb;       /* position angle of the bright limb's
                                      midpoint, from north through east       */
    double moon_libration_lat, moon_libration_lon; /* optical libration      */
    double moon_axis_angle;        /* position angle of the moon's axis       */
    double moon_parallactic;       /* topocentric parallactic angle           */
    double moon_semidiameter;      /* geocentric, radians                     */
    double sun_semidiameter;
    /* lunar eclipse (Danjon's enlarged shadow) */
    double umbral_magnitude, penumbral_magnitude;
    double umbra_radius, penumbra_radius, shadow_distance; /* angles        */
    /* solar eclipse seen by the observer (topocentric, unrefracted) */
    double sun_topo_semidiameter, moon_topo_semidiameter;
    double sun_moon_separation;    /* between the discs' centres               */
    double solar_obscuration;      /* fraction of the sun's disc area covered  */
    double solar_magnitude;        /* fraction of its diameter covered (> 1:
                                      total), 0 without contact              */
    double solar_flux_fraction;    /* the limb-darkened sun's light still
                                      reaching the observer, 0..1          */
    /* day-night fade factors (Mueller sec. 5; during a deep solar eclipse
     * they follow the dimmed sun) */
    double star_visibility, moon_visibility;
    /* stars: J2000 unit vector -> apparent direction of date in the
     * horizon frame = horizon * normalize(precession_nutation * v + aberration) */
    double precession_nutation[9]; /* row-major, J2000 mean -> true of date  */
    double aberration[3];          /* Earth's velocity / c, equatorial of date */
    double horizon[9];             /* true equatorial of date -> horizon frame */
    double years_since_j2000;      /* for proper motion (TT, Julian years)    */
    double pressure_factor;        /* refraction scale for the altitude       */
    /* for the planets */
    double earth_helio[3];         /* the Earth from the sun: rectangular
                                      ecliptic of date (VSOP87), au           */
    double observer_eq[3];         /* the observer from the Earth's centre,
                                      true equator of date, km                */
} sky_astro;

/* Computes everything for one instant (UTC, taken as UT1) and observer.
 * Returns 0, or -1 with a message for a date outside the supported span,
 * a latitude outside +-90 degrees or a non-finite input. */
int sky_astro_compute(double jd_ut, const sky_astro_observer *obs, sky_astro *out, char *err, size_t err_len);
/* The same with a given Delta T (seconds), e.g. another program's, so that
 * both turn the Earth alike when compared. */
int sky_astro_compute_dt(double jd_ut, double delta_t, const sky_astro_observer *obs, sky_astro *out, char *err,
                         size_t err_len);

/* The costly parts of the astronomy are functions of TT alone: the Earth's
 * VSOP87 place (l, b, r) and the sums of the moon's series (Meeus 47.A-B).
 * They are evaluated at nodes SKY_ASTRO_NODES_PER_DAY to a day (on a grid
 * fixed in TT) and interpolated linearly between the two around an
 * instant: the error is h^2/8 of their second derivative, under 0.05" for
 * the moon (its equation of the centre, 6.3 deg at 13 deg a day; 0.03"
 * measured) and 0.001" for the sun. A cache keeps the nodes last used (four: the time
 * slider asks for two instants a frame, up to the equation of time apart),
 * so a sky whose clock moves evaluates the series once every quarter of an
 * hour of its time instead of twice a frame. The result is the same with
 * or without the cache, whatever was asked before: it only saves work. */
#define SKY_ASTRO_NODES_PER_DAY 96.0
#define SKY_ASTRO_CACHE_NODES 4
typedef struct sky_astro_node {
    double index;              /* jd_tt * SKY_ASTRO_NODES_PER_DAY, whole */
    double earth_lbr[3];       /* heliocentric ecliptic of date, rad/au  */
    double moon_sums[3];       /* sum l, sum b (1e-6 deg), sum r (m)     */
    unsigned last_use;
} sky_astro_node;
typedef struct sky_astro_cache {
    sky_astro_node node[SKY_ASTRO_CACHE_NODES];
    int count;                 /* nodes held; zero-initialise            */
    unsigned uses;
} sky_astro_cache;

/* sky_astro_compute_dt with a cache (NULL: none). */
int sky_astro_compute_cached(double jd_ut, double delta_t, const sky_astro_observer *obs, sky_astro_cache *cache,
                             sky_astro *out, char *err, size_t err_len);

/* A catalogue star: J2000 position, proper motion (mas/yr, RA component
 * times cos dec). */
typedef struct sky_star {
    int hip;
    double ra, dec;
    double pm_ra, pm_dec;
    float vmag, bv;
} sky_star;

/* Apparent topocentric place of a star for the state's instant: refracted
 * and geometric altitude, azimuth; dir is the refracted horizon vector. */
void sky_astro_star(const sky_astro *a, const sky_star *star, double *alt, double *alt_geometric, double *az,
                    double dir[3]);

/* Atmospheric refraction (Saemundsson 1986, as in Meeus 16.4) for a true
 * altitude h, scaled by pressure_factor; continuous and finite for every
 * h: below -1 degree it tapers linearly to 0 at -6 degrees. */
double sky_refraction(double h, double pressure_factor);

/* Limb darkening of the drawn and eclipsed sun: I(mu) = 1 - u (1 - mu)
 * (Schneegans et al. eq. 1, u = 0.6; sun.frag uses the same profile). */
#define SKY_SUN_LIMB_DARKENING 0.6

/* A solar eclipse from its discs: angular radii of sun and moon and the
 * separation of their centres (radians, any non-negative values). Gives
 * the fraction of the sun's area covered, the eclipse magnitude (fraction
 * of the sun's diameter covered; above 1 when total) and the fraction of
 * the limb-darkened disc's light left uncovered. */
void sky_solar_eclipse(double sun_radius, double moon_radius, double separation, double *obscuration,
                       double *magnitude, double *flux_fraction);

/* The sky's brightness left at the zenith and at the horizon during a
 * solar eclipse, as fractions of the uneclipsed sky's: the light of the
 * uncovered sun plus, around totality, what the air outside the moon's
 * shadow scatters in (brightest along the horizon). */
#define SKY_ECLIPSE_ZENITH_RESIDUAL 3e-4
#define SKY_ECLIPSE_HORIZON_RESIDUAL 1.5e-3

/* ---- planets ----------------------------------------------------------------------- */

enum { SKY_ASTRO_MERCURY, SKY_ASTRO_VENUS, SKY_ASTRO_MARS, SKY_ASTRO_JUPITER, SKY_ASTRO_SATURN, SKY_ASTRO_PLANETS };

/* A planet's heliocentric state from its VSOP87D series at jd_tt:
 * position (au) and velocity (au/day), rectangular ecliptic of date. The
 * series cost some 70-350 terms a planet; a state serves
 * sky_astro_planet_place for instants near jd_tt (see there). */
typedef struct sky_planet_state {
    double jd_tt;
    double pos[3], vel[3];
} sky_planet_state;
void sky_planet_state_at(int planet, double jd_tt, sky_planet_state *st);
/* How far from its instant a state serves: within it the Taylor step
 * (position, velocity, the sun's pull) keeps Mercury, the fastest, within
 * 0.5" (tests/test_planets.c measures it). */
#define SKY_PLANET_STATE_DAYS 0.3

typedef struct sky_astro_planet {
    sky_astro_body body;           /* apparent place; distance_km geocentric  */
    double distance_au;            /* geocentric (light time's distance)      */
    double sun_distance_au;        /* heliocentric                            */
    double phase_angle;            /* sun-planet-earth angle                  */
    double illuminated;            /* fraction of the disc lit, 0..1          */
    double vmag;                   /* V magnitude (Mallama & Hilton 2018)     */
    double diameter;               /* apparent equatorial diameter, radians   */
    double ring_tilt;              /* Saturn: the Earth's latitude over the
                                      rings' plane (Meeus ch. 45's B); else 0 */
    double bv;                     /* measured B-V colour of the planet       */
} sky_astro_planet;

/* The planet's apparent topocentric place and brightness at a's instant
 * (Meeus ch. 33: the planet at t minus the light time seen from the Earth
 * at t, the FK5 correction, nutation and annual aberration; parallax and
 * refraction as for the moon), from a state of the planet within
 * SKY_PLANET_STATE_DAYS of that instant. */
void sky_astro_planet_place(const sky_astro *a, int planet, const sky_planet_state *st, sky_astro_planet *out);
/* V magnitude (Mallama & Hilton 2018) at distances r from the sun and
 * delta from the observer (au), phase angle alpha; ring_lat: Saturn's
 * effective latitude over its rings (the root of the sun's and the
 * Earth's, 0 when they are on opposite sides); helio_lon: Mars's
 * heliocentric ecliptic longitude, for its season term. Radians. */
double sky_astro_planet_magnitude(int planet, double r_au, double delta_au, double alpha, double ring_lat,
                                  double helio_lon);
/* A body's topocentric horizon place (alt, az, dirs, topo_distance_km)
 * from its geocentric apparent ra, dec and distance_km, for a's observer
 * and instant: how a planet's place of an instant moments ago follows the
 * sky's turning. */
void sky_astro_topocentric(const sky_astro *a, sky_astro_body *b);
/* The planet's B-V (what sky_astro_planet.bv holds). */
double sky_astro_planet_bv(int planet);
/* "mercury", ... for SKY_ASTRO_MERCURY...; NULL out of range. */
const char *sky_astro_planet_name(int planet);

/* Horizon-frame unit vector of an altitude and azimuth. */
void sky_horizon_vector(double alt, double az, double out[3]);

#endif
