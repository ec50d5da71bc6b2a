#!/usr/bin/env python3
"""Writes tests/data/planets_reference.txt: the planets as PyEphem sees them.

PyEphem (Debian's python3-ephem; Brandon Rhodes' wrapper of XEphem's
libastro, whose planets come from VSOP87 to arcsecond level) is the oracle
for libsky's planet positions and magnitudes: ERFA's only planet routine,
eraPlan94, is good to about 1' and cannot check 20".

    python3 tools/planet-reference.py > tests/data/planets_reference.txt

1 000 instants drawn (fixed seed) over 1800..2200, each with its own
observer (latitude -60..70, any longitude, altitude 0..2000 m). Per instant
and planet, one row:

    jd_ut delta_t_s lat_deg lon_deg alt_m planet alt_deg az_deg dist_au vmag phase vmag_mh

alt is the topocentric apparent altitude without refraction (pressure 0),
az from north through east, dist the geocentric distance, vmag PyEphem's
visual magnitude (0.01; libastro's formulas, after Harris 1961), phase the
illuminated percentage, vmag_mh the magnitude of Mallama & Hilton 2018
(the formulas libsky uses, written out again below) on PyEphem's
geometry: its distances, phase angle, Mars's heliocentric longitude and
Saturn's ring tilts toward the sun and the Earth. delta_t is
PyEphem's own TT - UT, which the test uses so that both sides turn the
Earth alike (the extrapolations of Delta T differ by minutes by 2200).
"""
import math
import random

import ephem

PLANETS = [("mercury", ephem.Mercury), ("venus", ephem.Venus), ("mars", ephem.Mars),
           ("jupiter", ephem.Jupiter), ("saturn", ephem.Saturn)]
DUBLIN_JD = 2415020.0  # ephem.Date counts days from 1899 Dec 31 12:00

# Mallama (2007, Icarus 192, 404) table 8: Mars's season term every 10
# degrees of Ls from 0 to 360.
MARS_SEASON = [-0.029, -0.017, -0.014, -0.006, -0.018, -0.020, -0.014, -0.030, -0.008, -0.040,
               -0.024, -0.037, -0.036, -0.032, 0.010, 0.010, -0.001, 0.044, 0.025, -0.004,
               -0.016, -0.008, 0.029, -0.054, -0.033, 0.055, 0.017, 0.052, 0.006, 0.087,
               0.006, 0.064, 0.030, 0.019, -0.030, -0.017, -0.029]


def mallama_hilton(name, r, delta, alpha, body):
    """V of Mallama & Hilton 2018 (Astronomy and Computing 25, 10), eq. 2-10."""
    a = alpha
    if name == "mercury":
        v = (-0.613 + 6.3280e-02 * a - 1.6336e-03 * a**2 + 3.3644e-05 * a**3
             - 3.4265e-07 * a**4 + 1.6893e-09 * a**5 - 3.0334e-12 * a**6)
    elif name == "venus":
        if a < 163.7:
            v = -4.384 - 1.044e-03 * a + 3.687e-04 * a**2 - 2.814e-06 * a**3 + 8.938e-09 * a**4
        else:
            v = 236.05828 - 2.81914 * a + 8.39034e-03 * a**2
    elif name == "mars":
        if a <= 50.0:
            v = -1.601 + 2.267e-02 * a - 1.302e-04 * a**2
        else:
            v = -0.367 - 0.02573 * a + 0.0003445 * a**2
        ls = ((math.degrees(body.hlon) - 85.0) % 360.0) / 10.0
        i = min(int(ls), 35)
        v += MARS_SEASON[i] + (ls - i) * (MARS_SEASON[i + 1] - MARS_SEASON[i])
    elif name == "jupiter":
        if a <= 12.0:
            v = -9.395 - 3.7e-04 * a + 6.16e-04 * a**2
        else:
            x = a / 180.0
            v = -9.428 - 2.5 * math.log10(1.0 - 1.507 * x - 0.363 * x**2 - 0.062 * x**3
                                          + 2.809 * x**4 - 1.876 * x**5)
    else:
        prod = body.earth_tilt * body.sun_tilt
        lat = math.sqrt(prod) if prod > 0 else 0.0
        sb = math.sin(min(lat, math.radians(27.0)))
        v = -8.914 - 1.825 * sb + 0.026 * a - 0.378 * sb * math.exp(-2.25 * a)
    return v + 5.0 * math.log10(r * delta)


def main():
    rng = random.Random(20261124)
    jd_1800 = 2378496.5  # 1800 January 1.0
    jd_2200 = 2524593.5  # 2200 January 1.0
    print("# planets as PyEphem %s sees them (tools/planet-reference.py); columns:" % ephem.__version__)
    print("# jd_ut delta_t_s lat_deg lon_deg alt_m planet alt_deg az_deg dist_au vmag phase_percent vmag_mh")
    for _ in range(1000):
        jd = rng.uniform(jd_1800, jd_2200)
        lat = rng.uniform(-60.0, 70.0)
        lon = rng.uniform(-180.0, 180.0)
        elev = rng.uniform(0.0, 2000.0)
        obs = ephem.Observer()
        obs.date = ephem.Date(jd - DUBLIN_JD)
        obs.lat = math.radians(lat)
        obs.lon = math.radians(lon)
        obs.elevation = elev
        obs.pressure = 0.0  # no refraction: geometric altitude
        obs.epoch = obs.date
        dt = ephem.delta_t(obs.date)
        sun = ephem.Sun()
        sun.compute(obs)
        for name, cls in PLANETS:
            body = cls()
            body.compute(obs)
            r, delta, big_r = body.sun_distance, body.earth_distance, sun.earth_distance
            cos_alpha = (r * r + delta * delta - big_r * big_r) / (2.0 * r * delta)
            alpha = math.degrees(math.acos(max(-1.0, min(1.0, cos_alpha))))
            print("%.8f %.3f %.6f %.6f %.1f %s %.7f %.7f %.9f %.2f %.4f %.3f" %
                  (jd, dt, lat, lon, elev, name, math.degrees(body.alt), math.degrees(body.az),
                   delta, body.mag, body.phase, mallama_hilton(name, r, delta, alpha, body)))


if __name__ == "__main__":
    main()
