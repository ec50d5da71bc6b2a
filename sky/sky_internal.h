/*
 * The inside of the sky handle, for sky.c and the white-box tests. No file
 * of the library below sky.c includes it: the rooms see the shared
 * context (core.h) and their own state only (docs/ARCHITECTURE.md).
 */
#ifndef SKY_INTERNAL_H
#define SKY_INTERNAL_H

#include "atmosphere/atmosphere.h"
#include "camera.h"
#include "catalog.h"
#include "core.h"
#include "aerial.h"
#include "irradiance.h"
#include "disc.h"
#include "exposure.h"
#include "layer.h"
#include "observer.h"
#include "solar_eclipse.h"

struct sky {
    sky_core core;                        /* what every room reads          */
    void *layer_state[SKY_LAYER_COUNT];   /* each layer's own, by its slot  */
    sky_dome_snippets dome_snippets;      /* of the enabled layers          */
    GLuint vao;                           /* CORE33 only                    */
    char error[256];
    sky_stats stats;
    sky_irradiance_cache irradiance;      /* sky_get_irradiance_sh's          */
    GLuint capture_fbo;                   /* sky_capture_environment's        */
    int capture_overwrote[4];             /* x, y, w, h of the host's draw
                                             buffer its last call drew into
                                             (no FBO), else zero              */
    sky_aerial_state aerial;              /* sky_get_aerial_perspective's and
                                             sky_aerial_bind's                */
};

#endif /* SKY_INTERNAL_H */
