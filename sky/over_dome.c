/*
 * Programs of the layers drawn over the dome (the sun, the moon, the
 * stars, the planets, the flicker stars): what hides them behind the
 * dome's front layers, either those layers' own snippets or, where the
 * dome is drawn into an image, that image's alpha (dome_cover.glsl). The
 * dome's composite pass reads the same image through the same uniforms.
 */
#include "layer.h"

#include <stdlib.h>

/* The image's uniforms (where a fragment finds itself in it comes from
 * the common u_viewport). */
static const sky_uniform_desc image_uniforms[] = {
    SKY_UT("u_dome_tex", SKY_TEX_DOME),
    SKY_UF("u_dome_texel", SKY_U_F2, dome_texel),
    SKY_UF("u_dome_scale", SKY_U_F2, dome_scale),
};
const sky_snippet sky_dome_image_snippet = {NULL, NULL, image_uniforms, SKY_UNIFORM_COUNT(image_uniforms),
                                            NULL, NULL, NULL};
const sky_snippet sky_dome_cover_snippet = {"SKY_HAS_DOME_COVER", "dome_cover.glsl", image_uniforms,
                                            SKY_UNIFORM_COUNT(image_uniforms), NULL, NULL, NULL};
/* without NPOT textures the image is the corner of a power of two */
const sky_snippet sky_dome_corner_snippet = {"SKY_DOME_CORNER", NULL, NULL, 0, NULL, NULL, NULL};

int sky_program_build_over_dome(sky_core *s, const sky_dome_snippets *dome, sky_program *p, const char *vert_main,
                                const char *frag_main, const sky_snippet *const *own, int own_count, char *err,
                                size_t err_len)
{
    /* the front layers' own snippets, or the image's cover (and corner) */
    int fronts = s->dome_divisor && dome->front_count ? 1 + !s->caps.npot : dome->front_count, n = 0;
    const sky_snippet **list = malloc(sizeof *list * (size_t)(fronts + own_count + 1));
    if (!list) {
        sky_format(err, err_len, "out of memory for %s", frag_main);
        return -1;
    }
    if (s->dome_divisor && dome->front_count) {
        list[n++] = &sky_dome_cover_snippet;
        if (!s->caps.npot) list[n++] = &sky_dome_corner_snippet;
    } else
        for (int i = 0; i < dome->front_count; i++) list[n++] = dome->front[i];
    for (int i = 0; i < own_count; i++) list[n++] = own[i];
    int rc = sky_program_build(s, p, vert_main, frag_main, list, n, err, err_len);
    free(list);
    return rc;
}
