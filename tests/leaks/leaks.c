/*
 * Leak check: N cycles of create, draw, destroy in one GL context, built
 * with LeakSanitizer (make builds it as build/bin/sky-leaks). LSan reports
 * any block the library leaked when the process exits; Mesa's own
 * allocations are suppressed in lsan.supp by library name only.
 */
#include "osmesa_ctx.h"
#include "sky.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        static const unsigned masks[4] = {0, SKY_FEATURES_NONE, SKY_CLOUDS, SKY_SUN | SKY_FLICKER_STARS};
        cfg.features = masks[i % 4];
        sky *s = sky_create(&cfg, err, sizeof err);
        if (!s) {
            fprintf(stderr, "sky-leaks: cycle %d: %s\n", i, err);
            failures++;
            continue;
        }
        if (sky_update(s, 0.5) != SKY_OK || sky_draw(s, view, proj) != SKY_OK) failures++;
        sky_destroy(s);
    }
    /* a failing create must not leak either */
    sky_config bad;
    memset(&bad, 0, sizeof bad);
    bad.get_proc_address = sky_osmesa_loader();
    bad.texture_dir = "/dev/null/none";
    bad.features = SKY_MOON;
    if (sky_create(&bad, err, sizeof err) != NULL) failures++;
    sky_osmesa_destroy(&ctx);
    printf("sky-leaks: %d create/draw/destroy cycles, %d failures\n", cycles, failures);
    return failures ? 1 : 0;
}
