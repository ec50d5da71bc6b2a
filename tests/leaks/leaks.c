/*
 * Leak check: N cycles of create, draw, destroy in one GL context, built
 * with AddressSanitizer over the same objects as the ASan test runner
 * (make builds it as build/bin/sky-leaks). Its LeakSanitizer, run with
 * ASAN_OPTIONS=detect_leaks=1 (api_leaks_1000_cycles), reports any block
 * the library leaked when the process exits; Mesa's own allocations are
 * suppressed in lsan.supp by library name only.
 */
#include "osmesa_ctx.h"
#include "sky.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int main(int argc, char **argv)
{
    int cycles = argc > 1 ? atoi(argv[1]) : 1000;
    char err[512];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 64, 64, SKY_GL_AUTO, 0, err, sizeof err)) {
        fprintf(stderr, "sky-leaks: %s\n", err);
        return 1;
    }
    float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1.02f, -1, 0, 0, -0.2f, 0};
    int failures = 0;
    for (int i = 0; i < cycles; i++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.get_proc_address = sky_osmesa_loader();
        /* vary the features so every create path is walked */
        static const unsigned masks[5] = {0, SKY_FEATURES_NONE, SKY_CLOUDS, SKY_SUN | SKY_FLICKER_STARS,
                                          SKY_MOON | SKY_ECLIPSE | SKY_STARS | SKY_STARMAP | SKY_CLOUDS};
        cfg.features = masks[i % 5];
        sky *s = sky_create(&cfg, err, sizeof err);
        if (!s) {
            fprintf(stderr, "sky-leaks: cycle %d: %s\n", i, err);
            failures++;
            continue;
        }
        if (sky_update(s, 0.5) != SKY_OK || sky_draw(s, view, proj) != SKY_OK) failures++;
        sky_destroy(s);
    }
    /* failing creates must not leak either: one refused before any GL
     * work, one that fails half-way (a broken override texture after the
     * dome and other resources exist) */
    sky_config bad;
    memset(&bad, 0, sizeof bad);
    bad.get_proc_address = sky_osmesa_loader();
    bad.features = SKY_ECLIPSE; /* needs SKY_MOON */
    sky *s1 = sky_create(&bad, err, sizeof err);
    if (s1) {
        failures++;
        sky_destroy(s1);
    }
    char dir[] = "/tmp/sky-leaks-XXXXXX";
    if (mkdtemp(dir)) {
        char path[64];
        snprintf(path, sizeof path, "%s/moon.png", dir);
        FILE *f = fopen(path, "wb");
        if (f) {
            fputs("not a png", f);
            fclose(f);
        }
        bad.features = SKY_MOON | SKY_STARS | SKY_CLOUDS;
        bad.texture_dir = dir;
        sky *s2 = sky_create(&bad, err, sizeof err);
        if (s2 || !strstr(err, "moon.png")) {
            fprintf(stderr, "sky-leaks: a broken moon.png must fail: %s\n", err);
            failures++;
            sky_destroy(s2);
        }
        remove(path);
        rmdir(dir);
    }
    sky_osmesa_destroy(&ctx);
    printf("sky-leaks: %d create/draw/destroy cycles, %d failures\n", cycles, failures);
    return failures ? 1 : 0;
}
