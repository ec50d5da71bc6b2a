/*
 * The bottom module's functions (core.h): numeric guards, clocks, error
 * text. Nothing here knows a layer, GL or the sky handle.
 */
#include "core.h"

#include <math.h>
#include <stdio.h>
#include <time.h>

double sky_wrap(double x, double period)
{
    double r = fmod(x, period);
    if (r < 0.0) r += period;
    return r >= period ? 0.0 : r; /* fmod of -tiny + period rounds to period */
}

double sky_phase_advance(double phase, double rate, double dt)
{
    /* whole cycles leave dt first: rate * dt cannot overflow, and a step
     * shorter than one cycle is used exactly as given */
    if (rate == 0.0) return phase;
    return sky_wrap(phase + rate * sky_wrap(dt, 1.0 / fabs(rate)), 1.0);
}

double sky_smoothstep(double e0, double e1, double x)
{
    double t = sky_clampd((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

void sky_mat3_mul(const double a[9], const double b[9], double out[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double acc = 0.0;
            for (int k = 0; k < 3; k++) acc += a[i * 3 + k] * b[k * 3 + j];
            out[i * 3 + j] = acc;
        }
}

void sky_j2000_to_horizon_mat4(const sky_astro *a, int inverse, float out[16])
{
    double m[9];
    sky_mat3_mul(a->horizon, a->precession_nutation, m);
    for (int i = 0; i < 16; i++) out[i] = i == 15 ? 1.0f : 0.0f;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out[inverse ? i * 4 + j : j * 4 + i] = (float)m[i * 3 + j];
}

#if defined(_WIN32)
/* kernel32's counter, declared here rather than through windows.h, whose
 * macros (near, far, min, max) would reach the code after it in one
 * translation unit (make amalgamation); MinGW's msvcrt has no
 * timespec_get */
__declspec(dllimport) int __stdcall QueryPerformanceCounter(long long *count);
__declspec(dllimport) int __stdcall QueryPerformanceFrequency(long long *frequency);

double sky_now_ms(void)
{
    long long count = 0, frequency = 0;
    QueryPerformanceCounter(&count);
    QueryPerformanceFrequency(&frequency);
    return frequency > 0 ? (double)count * 1e3 / (double)frequency : 0.0;
}
#else
double sky_now_ms(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
#endif

void sky_format(char *buf, size_t len, const char *fmt, ...)
{
    if (!buf || len == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, len, fmt, ap);
    va_end(ap);
}
