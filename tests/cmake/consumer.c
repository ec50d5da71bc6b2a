/*
 * A host of libsky that needs no GL context, built by tests/test_build.c
 * through each way a CMake project takes the library (find_package after
 * an install, add_subdirectory) and through the installed sky.pc. It
 * includes sky.h alone and prints what the runner checks: the version of
 * the library it linked, and where that library puts the sun. It fails
 * (exit 1) when the library linked is not the header's version.
 */
#include <sky.h>
#include <stdio.h>

int main(void)
{
    unsigned v = sky_version();
    unsigned want = (unsigned)SKY_VERSION_MAJOR << 16 | (unsigned)SKY_VERSION_MINOR << 8 | (unsigned)SKY_VERSION_PATCH;
    printf("sky %u.%u.%u\n", v >> 16, v >> 8 & 0xffu, v & 0xffu);
    if (v != want) {
        printf("sky.h says %d.%d.%d\n", SKY_VERSION_MAJOR, SKY_VERSION_MINOR, SKY_VERSION_PATCH);
        return 1;
    }
    /* Greenwich on the 2024 June solstice at 12:00 UTC: the sun near the
     * meridian, at 90 - 51.48 + 23.44, about 62 degrees up */
    sky_observer obs = {0};
    obs.julian_day_utc = sky_julian_day(2024, 6, 20, 12, 0, 0.0);
    obs.latitude_deg = 51.48;
    sky_astronomy astro;
    char err[256];
    if (sky_compute_astronomy(&obs, 0.5f, NULL, 0, NULL, &astro, err, sizeof err) != SKY_OK) {
        printf("sky_compute_astronomy: %s\n", err);
        return 1;
    }
    printf("sun at %.1f degrees, azimuth %.1f\n", astro.sun.alt_deg, astro.sun.az_deg);
    return 0;
}
