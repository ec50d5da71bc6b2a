/*
 * API tests: defaults, input validation, lifecycle, GL hygiene.
 */
#define GL_GLEXT_PROTOTYPES 1
#include "test.h"
#include "sky_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void default_camera(float view[16], float proj[16])
{
    scene sc = scene_default();
    scene_camera(&sc, view, proj);
}

TEST(api_zero_config_renders)
{
    fixture f;
    sky_config zero;
    memset(&zero, 0, sizeof zero); /* zero = defaults; only the loader is added */
    CHECK(fixture_open(&f, SKY_GL_AUTO, &zero) == 0, "a zeroed config must create a sky");
    if (!f.s) return;
    float view[16], proj[16];
    default_camera(view, proj);
    CHECK(sky_draw(f.s, view, proj) == SKY_OK, "draw: %s", sky_last_error(f.s));
    CHECK(glGetError() == GL_NO_ERROR, "no GL error after a draw");
    sky_stats st;
    sky_get_stats(f.s, &st);
    CHECK(st.features == SKY_FEATURES_DEFAULT, "default features, got 0x%x", st.features);
    CHECK(st.profile == SKY_GL_CORE33, "AUTO on a core context picks CORE33");
    fixture_close(&f);
}

TEST(api_rejects_null_and_bad_config)
{
    char err[256];
    CHECK(sky_create(NULL, err, sizeof err) == NULL && strstr(err, "NULL"), "NULL config: %s", err);
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "get_proc_address"), "no loader: %s", err);
    CHECK(sky_create(NULL, NULL, 0) == NULL, "NULL err buffer is fine");

    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 32, 32, SKY_GL_AUTO, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.atmosphere = (sky_atmosphere_path)99;
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "out of range"), "bad path: %s", err);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    cfg.luts.skyview_width = 2000; /* tables: 4..1024 */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "luts"), "bad table size: %s", err);
    cfg.luts.skyview_width = 0;
    cfg.luts.skyview_steps = 300; /* samples: 1..256 */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "luts"), "bad sample count: %s", err);
    cfg.luts.skyview_steps = 0;
    cfg.atmosphere = SKY_ATMOSPHERE_BLEND;
    cfg.blend_manual = 1;
    cfg.blend_weight = NAN;
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "blend_weight"), "NaN blend: %s", err);
    cfg.blend_manual = 0;
    cfg.blend_weight = 0.0f;
    /* the blend mixes an analytic path: RAYLEIGH (0) or PREETHAM, nothing else */
    static const sky_atmosphere_path bad_partners[] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE,
                                                       SKY_ATMOSPHERE_BLEND, (sky_atmosphere_path)-1,
                                                       (sky_atmosphere_path)99};
    for (size_t i = 0; i < sizeof bad_partners / sizeof bad_partners[0]; i++) {
        cfg.blend_partner = bad_partners[i];
        CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "blend_partner"), "bad partner %d: %s",
              (int)bad_partners[i], err);
    }
    cfg.blend_partner = SKY_ATMOSPHERE_DEFAULT;
    cfg.atmosphere = SKY_ATMOSPHERE_DEFAULT;
    cfg.dome_divisor = 9; /* 0 (default) or 1..8 */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "dome_divisor"), "bad divisor: %s", err);
    cfg.dome_divisor = -1;
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "dome_divisor"), "negative divisor: %s", err);
    cfg.dome_divisor = 0;
    const float bad_ranges[] = {NAN, INFINITY, -1.0f, 0.005f, 16.5f}; /* 0 (default) or 0.01..16 stops */
    for (size_t i = 0; i < sizeof bad_ranges / sizeof bad_ranges[0]; i++) {
        cfg.exposure_range = bad_ranges[i];
        CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "exposure_range"), "bad range %g: %s",
              (double)bad_ranges[i], err);
    }
    cfg.exposure_range = 0.0f;
    cfg.tone_map = (sky_tone_map)3; /* hue, filmic or neutral */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "tone_map"), "bad tone map: %s", err);
    cfg.tone_map = SKY_TONE_MAP_HUE;
    cfg.features = 1u << 20; /* no such feature */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "not built yet"), "unknown feature: %s", err);
    cfg.features = 0;
    cfg.horizon_to_world[0] = 2.0f; /* not a rotation */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "rotation"), "bad rotation: %s", err);
    memset(cfg.horizon_to_world, 0, sizeof cfg.horizon_to_world);
    cfg.gl_profile = SKY_GL_COMPAT20; /* a core context cannot run GLSL 110 */
    CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "compatibility"), "compat on core: %s", err);
    cfg.gl_profile = SKY_GL_AUTO;
    cfg.texture_dir = "/nonexistent/dir"; /* no overrides there: embedded used */
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(s != NULL, "a missing override directory falls back to embedded: %s", err);
    sky_destroy(s);
    sky_destroy(NULL); /* must be harmless */

    /* NULL sky and NULL outputs */
    sky_params p = sky_default_params();
    CHECK(sky_set_params(NULL, &p) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_update(NULL, 0.1) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_draw(NULL, NULL, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_draw_fisheye(NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_get_stats(NULL, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_get_lighting(NULL, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_get_params(NULL, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(strlen(sky_last_error(NULL)) > 0, "last error of NULL says so");
    CHECK(!strcmp(sky_layer_name((sky_layer)42), "unknown"), "bad layer name");
    sky_osmesa_destroy(&ctx);
}

TEST(api_sliders_clamp_and_reject_nan)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    sky_params p = {0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f}, got;
    CHECK(sky_set_params(f.s, &p) == SKY_OK, "in-range sliders are accepted");
    sky_get_params(f.s, &got);
    CHECK(!memcmp(&p, &got, sizeof p), "sliders read back unchanged");

    sky_params wild = {-0.5f, 1.5f, INFINITY, -INFINITY, 2.0f, 0.5f};
    CHECK(sky_set_params(f.s, &wild) == SKY_CLAMPED, "out of range clamps");
    CHECK(strstr(sky_last_error(f.s), "clamped") != NULL, "message: %s", sky_last_error(f.s));
    sky_get_params(f.s, &got);
    CHECK(got.cover == 0.0f && got.height == 1.0f && got.density == 1.0f && got.sunset == 0.0f && got.speed == 1.0f,
          "clamped to 0..1: %g %g %g %g %g", got.cover, got.height, got.density, got.sunset, got.speed);

    sky_params nan_p = got;
    nan_p.time = NAN;
    nan_p.cover = 0.9f;
    CHECK(sky_set_params(f.s, &nan_p) == SKY_ERR_INVALID_ARGUMENT, "NaN is rejected");
    CHECK(strstr(sky_last_error(f.s), "time") != NULL, "message names the slider: %s", sky_last_error(f.s));
    sky_params after;
    sky_get_params(f.s, &after);
    CHECK(!memcmp(&after, &got, sizeof after), "a rejected call changes nothing");
    CHECK(sky_set_params(f.s, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL params");
    CHECK(sky_set_exposure_bias(f.s, NAN) == SKY_ERR_INVALID_ARGUMENT, "NaN exposure bias rejected");
    CHECK(sky_set_exposure_bias(f.s, 50.0f) == SKY_CLAMPED, "exposure bias clamped");
    CHECK(sky_set_exposure_bias(NULL, 0.0f) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_set_exposure_bias(f.s, 0.0f) == SKY_OK, "exposure bias 0");

    /* every slider at its extremes draws a finite frame */
    float view[16], proj[16];
    default_camera(view, proj);
    for (int corner = 0; corner < 64; corner++) {
        sky_params q = {(float)(corner & 1), (float)((corner >> 1) & 1), (float)((corner >> 2) & 1),
                        (float)((corner >> 3) & 1), (float)((corner >> 4) & 1), (float)((corner >> 5) & 1)};
        sky_set_params(f.s, &q);
        if (sky_draw(f.s, view, proj) != SKY_OK) {
            CHECK(0, "corner %d: %s", corner, sky_last_error(f.s));
            break;
        }
    }
    fixture_close(&f);
}

TEST(api_update_time_validation)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    CHECK(sky_update(f.s, 0.0) == SKY_OK, "dt 0 is fine");
    CHECK(sky_update(f.s, -1.0) == SKY_ERR_INVALID_ARGUMENT, "negative dt is rejected");
    CHECK(sky_update(f.s, NAN) == SKY_ERR_INVALID_ARGUMENT, "NaN dt is rejected");
    CHECK(sky_update(f.s, INFINITY) == SKY_ERR_INVALID_ARGUMENT, "infinite dt is rejected");
    CHECK(sky_set_elapsed(f.s, -5.0) == SKY_ERR_INVALID_ARGUMENT, "negative elapsed is rejected");
    CHECK(sky_update(f.s, 1e9) == SKY_OK, "a billion seconds at once is fine");
    CHECK(sky_update(f.s, 1e-300) == SKY_OK, "a denormal-sized step is fine");
    /* wrapped offsets stay in [0, 1) */
    const double *offsets = sky_clouds_offsets(f.s->layer_state[SKY_LAYER_CLOUDS]);
    double flicker = sky_flicker_clock(f.s->layer_state[SKY_LAYER_FLICKER]);
    for (int l = 0; l < SKY_CLOUD_LAYERS; l++)
        for (int i = 0; i < 2; i++)
            CHECK(offsets[l * 2 + i] >= 0.0 && offsets[l * 2 + i] < 1.0, "offset %d.%d = %g", l, i, offsets[l * 2 + i]);
    CHECK(flicker >= 0.0 && flicker < 1.0, "flicker clock %g", flicker);
    fixture_close(&f);
}

TEST(api_draw_rejects_bad_matrices)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    float view[16], proj[16], bad[16];
    default_camera(view, proj);
    CHECK(sky_draw(f.s, NULL, proj) == SKY_ERR_INVALID_ARGUMENT, "NULL view");
    memcpy(bad, view, sizeof bad);
    bad[5] = NAN;
    CHECK(sky_draw(f.s, bad, proj) == SKY_ERR_INVALID_ARGUMENT, "NaN view");
    memset(bad, 0, sizeof bad);
    CHECK(sky_draw(f.s, bad, proj) == SKY_ERR_INVALID_ARGUMENT, "zero view: %s", sky_last_error(f.s));
    CHECK(sky_draw(f.s, view, bad) == SKY_ERR_INVALID_ARGUMENT, "singular proj: %s", sky_last_error(f.s));
    /* a scaled, translated view still means the same directions */
    memcpy(bad, view, sizeof bad);
    for (int i = 0; i < 12; i++) bad[i] *= 3.0f;
    bad[12] = 100.0f;
    bad[13] = -50.0f;
    CHECK(sky_draw(f.s, bad, proj) == SKY_OK, "scaled view is accepted: %s", sky_last_error(f.s));
    /* looking straight up and straight down */
    scene sc = scene_default();
    for (int k = 0; k < 2; k++) {
        sc.pitch = k ? 90.0 : -90.0;
        scene_camera(&sc, view, proj);
        CHECK(sky_draw(f.s, view, proj) == SKY_OK, "pitch %g: %s", sc.pitch, sky_last_error(f.s));
    }
    CHECK(glGetError() == GL_NO_ERROR, "no GL error left behind");
    fixture_close(&f);
}

TEST(api_lighting_and_stats)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    sky_params p = sky_default_params();
    sky_lighting noon, night;
    p.time = 0.5f;
    sky_set_params(f.s, &p);
    sky_get_lighting(f.s, &noon);
    p.time = 0.0f;
    sky_set_params(f.s, &p);
    sky_get_lighting(f.s, &night);
    double len = sqrt(noon.sun_direction[0] * noon.sun_direction[0] + noon.sun_direction[1] * noon.sun_direction[1] +
                      noon.sun_direction[2] * noon.sun_direction[2]);
    CHECK(fabs(len - 1.0) < 1e-5, "sun direction is a unit vector (%g)", len);
    CHECK(noon.sun_direction[1] > 0.5f && noon.sun_direction[2] > 0.5f, "noon sun high in the south (+z)");
    CHECK(night.sun_direction[1] < -0.5f, "midnight sun below");
    CHECK(noon.sun_color[1] > 50.0f && night.sun_color[1] == 0.0f, "sunlight %g klx at noon, %g at night",
          noon.sun_color[1], night.sun_color[1]);
    CHECK(noon.ambient_color[2] > noon.ambient_color[0], "skylight is bluish");
    CHECK(noon.ambient_color[1] > 1000.0f * night.ambient_color[1], "day ambient >> night ambient");
    CHECK(noon.daylight == 1.0f && night.daylight == 0.0f, "daylight %g / %g", noon.daylight, night.daylight);
    CHECK(sky_get_lighting(f.s, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL out");

    sky_stats st;
    CHECK(sky_get_stats(f.s, &st) == SKY_OK, "stats");
    /* the clouds and the dome's image; dome programs by day, by night, by
     * night without clouds and below the horizon (by day and below the
     * horizon each twice: with the tone map's scotopic shift and without,
     * for while it is off), the image's two (view and all-sky), the
     * flicker stars' and the sun's */
    CHECK(st.textures == 2 && st.programs == 10, "2 textures and 10 programs by default, got %d and %d", st.textures,
          st.programs);
    /* the layers by index (sky_get_layer_stats): the ones created are the
     * feature mask's (the atmosphere always) */
    static const unsigned layer_feature[SKY_LAYER_COUNT] = {
        [SKY_LAYER_STARMAP] = SKY_STARMAP, [SKY_LAYER_STARS] = SKY_STARS, [SKY_LAYER_FLICKER] = SKY_FLICKER_STARS,
        [SKY_LAYER_MOON] = SKY_MOON,       [SKY_LAYER_SUN] = SKY_SUN,     [SKY_LAYER_CLOUDS] = SKY_CLOUDS,
        [SKY_LAYER_PLANETS] = SKY_PLANETS, [SKY_LAYER_AIRGLOW] = SKY_AIRGLOW, [SKY_LAYER_ZODIACAL] = SKY_ZODIACAL,
    };
    /* the layers after 0.5's, found by name (they have no constant) */
    static const struct {
        const char *name;
        unsigned feature;
    } later[] = {{"rainbow", SKY_RAINBOW}, {"halo", SKY_HALO}, {"aurora", SKY_AURORA}};
    enum { LATER = (int)(sizeof later / sizeof later[0]) };
    CHECK(sky_layer_count() == SKY_LAYER_COUNT + LATER, "sky_layer_count %d", sky_layer_count());
    size_t sum = 0;
    int same = 1;
    for (int l = 0; l < sky_layer_count(); l++) {
        unsigned feature = 0;
        if (l < SKY_LAYER_COUNT) feature = layer_feature[l];
        for (int k = 0; k < LATER && l >= SKY_LAYER_COUNT; k++)
            if (!strcmp(sky_layer_name((sky_layer)l), later[k].name)) feature = later[k].feature;
        CHECK(l < SKY_LAYER_COUNT || feature, "layer %d (%s) is a later layer the test knows", l,
              sky_layer_name((sky_layer)l));
        sky_layer_stats ls;
        if (sky_get_layer_stats(f.s, l, &ls) != SKY_OK) {
            CHECK(0, "layer %d: %s", l, sky_last_error(f.s));
            continue;
        }
        sum += ls.bytes;
        same &= ls.enabled == (l == SKY_LAYER_ATMOSPHERE || (st.features & feature) != 0) &&
                (ls.enabled || (!ls.drawn && !ls.draws && !ls.bytes));
    }
    sky_layer_stats moon, clouds, spare;
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_MOON, &moon) == SKY_OK && !moon.enabled &&
              sky_get_layer_stats(f.s, SKY_LAYER_CLOUDS, &clouds) == SKY_OK && clouds.enabled,
          "layer flags");
    CHECK(same, "sky_get_layer_stats agrees with sky_stats.features (and a layer left out shows nothing)");
    CHECK(sum == st.gpu_bytes, "per-layer bytes add up to gpu_bytes (%zu vs %zu)", sum, st.gpu_bytes);
    CHECK(sky_get_layer_stats(f.s, -1, &spare) == SKY_ERR_INVALID_ARGUMENT &&
              sky_get_layer_stats(f.s, sky_layer_count(), &spare) == SKY_ERR_INVALID_ARGUMENT &&
              sky_get_layer_stats(f.s, 0, NULL) == SKY_ERR_INVALID_ARGUMENT &&
              sky_get_layer_stats(NULL, 0, &spare) == SKY_ERR_INVALID_ARGUMENT,
          "sky_get_layer_stats refuses a bad index, a NULL sky or output");
    fixture_close(&f);
}

TEST(api_gl_objects_deleted)
{
    char err[256];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 32, 32, SKY_GL_AUTO, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = sky_osmesa_loader();
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        CHECK(0, "%s", err);
        sky_osmesa_destroy(&ctx);
        return;
    }
    float view[16], proj[16];
    default_camera(view, proj);
    sky_draw(s, view, proj);
    /* every name the context has given out (a fresh context numbers its
     * objects from 1): what is live now, and what survives sky_destroy */
    sky_stats st;
    sky_get_stats(s, &st);
    GLuint vao = s->vao;
    enum { NAMES = 256 };
    int textures = 0, programs = 0, buffers = 0;
    for (GLuint n = 1; n < NAMES; n++) {
        textures += glIsTexture(n) == GL_TRUE;
        programs += glIsProgram(n) == GL_TRUE;
        buffers += glIsBuffer(n) == GL_TRUE;
    }
    /* buffers: the dome's vertices, indices and image quad, the flicker
     * stars, the sun's grid (vertices and indices) */
    CHECK(textures == 2 && textures == st.textures && programs == st.programs && programs == 10 &&
              buffers == st.buffers && buffers == 6 && glIsVertexArray(vao) == GL_TRUE,
          "all objects live before destroy (textures %d, programs %d, buffers %d)", textures, programs, buffers);
    sky_destroy(s);
    int left = glIsVertexArray(vao) == GL_TRUE;
    for (GLuint n = 1; n < NAMES; n++)
        left += (glIsTexture(n) == GL_TRUE) + (glIsProgram(n) == GL_TRUE) + (glIsBuffer(n) == GL_TRUE);
    CHECK(left == 0, "%d GL objects survive sky_destroy", left);
    sky_osmesa_destroy(&ctx);
}

TEST(api_leaks_1000_cycles)
{
    char path[512], out[4096];
    char cmd[1024];
    /* SKY_LEAKS names the leak checker; set empty, it was not built for
     * this run (make check, the fast tier, builds no sanitizer programs,
     * and sets it so that a stale one from an earlier make test is not
     * run either). */
    const char *leaks = getenv("SKY_LEAKS");
    if (!leaks) leaks = bin_path("sky-leaks", path, sizeof path);
    FILE *program = *leaks ? fopen(leaks, "rb") : NULL;
    if (program) fclose(program);
    if (!program) {
        SKIP("no leak checker (%s): make test builds it", *leaks ? leaks : "SKY_LEAKS is empty");
        return;
    }
    /* sky-leaks is built with AddressSanitizer, whose LeakSanitizer runs
     * only with detect_leaks=1: set here, because the ASan runner that
     * also runs this test turns it off for itself in the environment the
     * child inherits. */
    snprintf(cmd, sizeof cmd,
             "ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=tests/leaks/lsan.supp:print_suppressions=0 %s 1000 2>&1",
             leaks);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "LeakSanitizer run exited %d:\n%s", rc, out);
    char *line = strstr(out, "cycles");
    if (line) NOTE("%.*s", (int)strcspn(line, "\n"), line);
}

/* ---- GL state ---------------------------------------------------------------- */

typedef struct gl_snapshot {
    GLint program, active, array_buffer, element_buffer, vao, viewport[4], scissor_box[4], tex[4];
    GLfloat clear_color[4];
    GLboolean blend, depth, cull, scissor, stencil, depth_mask, color_mask[4];
    GLint bsrc, bdst, bsrca, bdsta, beq, beqa, depth_func;
    GLint attrib_enabled[3], attrib_size[3], attrib_stride[3], attrib_buffer[3];
    GLint draw_framebuffer, read_framebuffer;
    GLint unpack[4], unpack_buffer, pack_alignment, polygon_mode[2];
    GLboolean framebuffer_srgb;
} gl_snapshot;

static void snapshot(gl_snapshot *g, int core)
{
    memset(g, 0, sizeof *g);
    glGetIntegerv(GL_CURRENT_PROGRAM, &g->program);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &g->active);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &g->array_buffer);
    if (core) glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &g->vao);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &g->draw_framebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &g->read_framebuffer);
    static const GLenum unpack[4] = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS,
                                     GL_UNPACK_SKIP_PIXELS};
    for (int i = 0; i < 4; i++) glGetIntegerv(unpack[i], &g->unpack[i]);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &g->unpack_buffer);
    glGetIntegerv(GL_PACK_ALIGNMENT, &g->pack_alignment);
    glGetIntegerv(GL_POLYGON_MODE, g->polygon_mode);
    g->framebuffer_srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &g->element_buffer);
    glGetIntegerv(GL_VIEWPORT, g->viewport);
    glGetIntegerv(GL_SCISSOR_BOX, g->scissor_box);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, g->clear_color);
    GLint active;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int i = 0; i < 4; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &g->tex[i]);
    }
    glActiveTexture((GLenum)active);
    g->blend = glIsEnabled(GL_BLEND);
    g->depth = glIsEnabled(GL_DEPTH_TEST);
    g->cull = glIsEnabled(GL_CULL_FACE);
    g->scissor = glIsEnabled(GL_SCISSOR_TEST);
    g->stencil = glIsEnabled(GL_STENCIL_TEST);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &g->depth_mask);
    glGetBooleanv(GL_COLOR_WRITEMASK, g->color_mask);
    glGetIntegerv(GL_BLEND_SRC_RGB, &g->bsrc);
    glGetIntegerv(GL_BLEND_DST_RGB, &g->bdst);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &g->bsrca);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &g->bdsta);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &g->beq);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &g->beqa);
    glGetIntegerv(GL_DEPTH_FUNC, &g->depth_func);
    for (GLuint i = 0; i < 3; i++) {
        glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &g->attrib_enabled[i]);
        glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_SIZE, &g->attrib_size[i]);
        glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_STRIDE, &g->attrib_stride[i]);
        glGetVertexAttribiv(i, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &g->attrib_buffer[i]);
    }
}

unsigned test_snippet_program(int core, const char *snippet, const char *body)
{
    const char *vs = core ? "#version 330 core\nin vec4 p;\nvoid main(){gl_Position=p;}\n"
                          : "#version 110\nattribute vec4 p;\nvoid main(){gl_Position=p;}\n";
    const char *head = core ? "#version 330 core\nout vec4 frag;\n#define FRAG frag\n"
                            : "#version 110\n#define FRAG gl_FragColor\n";
    const char *fs[3] = {head, snippet ? snippet : "", body};
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER), p = glCreateProgram();
    glShaderSource(v, 1, &vs, NULL);
    glShaderSource(f, 3, fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    GLint ok = 0;
    glGetShaderiv(f, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = "";
        glGetShaderInfoLog(f, sizeof log, NULL, log);
        CHECK(0, "a host's fragment stage with the snippet does not compile: %s", log);
    }
    glAttachShader(p, v);
    glAttachShader(p, f);
    glBindAttribLocation(p, 0, "p");
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    return p;
}

unsigned test_host_program(int core) { return test_snippet_program(core, NULL, "void main(){FRAG=vec4(1.0);}\n"); }

void test_fullscreen_triangle(int core, unsigned *vao, unsigned *buf)
{
    *vao = 0;
    if (core) {
        glGenVertexArrays(1, vao);
        glBindVertexArray(*vao);
    }
    static const float tri[6] = {-1, -1, 3, -1, -1, 3};
    glGenBuffers(1, buf);
    glBindBuffer(GL_ARRAY_BUFFER, *buf);
    glBufferData(GL_ARRAY_BUFFER, sizeof tri, tri, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray(0);
}

void test_fullscreen_free(unsigned vao, unsigned buf)
{
    glDeleteBuffers(1, &buf);
    if (vao) glDeleteVertexArrays(1, &vao);
}

/* Compares two snapshots; names the words that differ. */
static int same_state(const gl_snapshot *before, const gl_snapshot *after, const char *when)
{
    if (!memcmp(before, after, sizeof *before)) return 1;
    const GLint *a = (const GLint *)(const void *)before, *b = (const GLint *)(const void *)after;
    for (size_t i = 0; i < sizeof *before / sizeof(GLint); i++)
        if (a[i] != b[i]) NOTE("%s: word %zu: %d -> %d", when, i, a[i], b[i]);
    return 0;
}

/* A client outside the library: its own VAO, program, textures on four
 * units, draw and read framebuffers, viewport, scissor, blend, cull,
 * depth, sRGB conversion, polygon mode, pixel store and a bound pixel
 * unpack buffer; every value the same after sky_create, sky_draw,
 * sky_draw_fisheye and sky_destroy. Hillaire's path: its tables are built
 * and uploaded (COMPAT20: on the CPU, uploaded at draws). */
static void state_restored(sky_gl_profile profile)
{
    char err[256];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 32, 32, profile, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    int core = profile == SKY_GL_CORE33;
    /* drawing into a framebuffer of its own while reading from another
     * (sky_draw renders its dome's image through a third and must put
     * both back) */
    GLuint host_fbo[2], host_color[2];
    glGenTextures(2, host_color);
    glGenFramebuffers(2, host_fbo);
    for (int i = 0; i < 2; i++) {
        glBindTexture(GL_TEXTURE_2D, host_color[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glBindFramebuffer(GL_FRAMEBUFFER, host_fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, host_color[i], 0);
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, host_fbo[0]);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, host_fbo[1]);
    GLuint prog = test_host_program(core), vao = 0, buf = 0, tex[4], pbo = 0;
    if (core) {
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
    }
    glGenBuffers(1, &buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBufferData(GL_ARRAY_BUFFER, 64, NULL, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (const void *)0);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, (const void *)0);
    glGenTextures(4, tex);
    for (int i = 0; i < 4; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, tex[i]);
    }
    glActiveTexture(GL_TEXTURE2);
    glUseProgram(prog);
    glViewport(3, 4, 50, 40);
    glScissor(1, 2, 30, 20);
    glClearColor(0.25f, 0.5f, 0.75f, 0.125f);
    GLuint ebo = 0;
    glGenBuffers(1, &ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 16, (const void *)0);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 1);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 8);
    glGenBuffers(1, &pbo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
    glBufferData(GL_PIXEL_UNPACK_BUFFER, 64, NULL, GL_STREAM_DRAW);
    gl_snapshot before, after;
    snapshot(&before, core);

    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.atmosphere = SKY_ATMOSPHERE_HILLAIRE;
    cfg.gl_profile = profile;
    cfg.check_gl_errors = 1;
    cfg.get_proc_address = sky_osmesa_loader();
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(s != NULL, "sky_create: %s", err);
    snapshot(&after, core);
    CHECK(same_state(&before, &after, "sky_create"), "GL state differs after sky_create");
    if (s) {
        float view[16], proj[16];
        default_camera(view, proj);
        for (int k = 0; k < 2; k++) { /* the second draw: tables uploaded, the image resized */
            CHECK(sky_draw(s, view, proj) == SKY_OK, "draw: %s", sky_last_error(s));
            snapshot(&after, core);
            CHECK(same_state(&before, &after, "sky_draw"), "GL state differs after sky_draw");
        }
        CHECK(sky_draw_fisheye(s) == SKY_OK, "fisheye: %s", sky_last_error(s));
        snapshot(&after, core);
        CHECK(same_state(&before, &after, "sky_draw_fisheye"), "GL state differs after sky_draw_fisheye");
        sky_destroy(s);
        snapshot(&after, core);
        CHECK(same_state(&before, &after, "sky_destroy"), "GL state differs after sky_destroy");
    }
    CHECK(glGetError() == GL_NO_ERROR, "no GL error");
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glDeleteBuffers(1, &pbo);
    glUseProgram(0);
    glDeleteProgram(prog);
    glDeleteTextures(4, tex);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(2, host_fbo);
    glDeleteTextures(2, host_color);
    glDeleteBuffers(1, &buf);
    glDeleteBuffers(1, &ebo);
    if (core) glDeleteVertexArrays(1, &vao);
    sky_osmesa_destroy(&ctx);
}

TEST(gl_state_restored_core) { state_restored(SKY_GL_CORE33); }
TEST(gl_state_restored_compat) { state_restored(SKY_GL_COMPAT20); }

/* The host's raster state that would change the sky's picture is set
 * aside for its draws: filled polygons whatever glPolygonMode says, and no
 * second sRGB encoding by a framebuffer with GL_FRAMEBUFFER_SRGB on (the
 * 8-bit output is encoded by the sky). The same frame drawn into a plain
 * RGBA8 target and into an sRGB one under those settings: the same bytes. */
TEST(gl_host_raster_state_ignored)
{
    enum { W = 64, H = 48 };
    fixture f;
    if (fixture_open_sized(&f, W, H, 0, SKY_GL_CORE33, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    GLuint fbo[2], color[2];
    glGenTextures(2, color);
    glGenFramebuffers(2, fbo);
    for (int i = 0; i < 2; i++) {
        glBindTexture(GL_TEXTURE_2D, color[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, i ? GL_SRGB8_ALPHA8 : GL_RGBA8, W, H, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color[i], 0);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    static unsigned char px[2][W * H * 4];
    float view[16], proj[16];
    default_camera(view, proj);
    glViewport(0, 0, W, H);
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[i]);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        if (i) {
            glEnable(GL_FRAMEBUFFER_SRGB);
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        }
        CHECK(sky_draw(f.s, view, proj) == SKY_OK, "draw: %s", sky_last_error(f.s));
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px[i]);
    }
    int worst = 0;
    for (int k = 0; k < W * H * 4; k++)
        if (k % 4 != 3) worst = abs(px[0][k] - px[1][k]) > worst ? abs(px[0][k] - px[1][k]) : worst;
    NOTE("largest difference between the plain and the sRGB, wireframe-mode target: %d", worst);
    CHECK(worst <= 1, "the sky ignores the host's polygon mode and sRGB conversion (%d levels apart)", worst);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(2, fbo);
    glDeleteTextures(2, color);
    fixture_close(&f);
}

static sky *sky_in(sky_osmesa *ctx, int check, char *err, size_t len)
{
    if (sky_osmesa_create(ctx, 32, 32, SKY_GL_AUTO, 0, err, len)) return NULL;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.check_gl_errors = check;
    return sky_create(&cfg, err, len);
}


/* GL errors the host left pending are the host's: sky_draw neither takes
 * them (by default it calls no glGetError) nor reports them as its own
 * (with cfg.check_gl_errors it says they were pending before the call).
 * No current context, and a context that is not the sky's, are found
 * without glGetError. */
TEST(gl_errors_left_to_host_and_contexts_checked)
{
    char err[256];
    sky_osmesa a, b;
    sky *plain = sky_in(&a, 0, err, sizeof err);
    CHECK(plain != NULL, "sky: %s", err);
    sky *checking = sky_in(&b, 1, err, sizeof err);
    CHECK(checking != NULL, "checking sky: %s", err);
    if (!plain || !checking) return;
    float view[16], proj[16];
    default_camera(view, proj);

    sky_osmesa_make_current(&a);
    glEnable(0xBEEF); /* the host's mistake: GL_INVALID_ENUM pending */
    CHECK(sky_draw(plain, view, proj) == SKY_OK, "draw: %s", sky_last_error(plain));
    GLenum e = glGetError();
    CHECK(e == GL_INVALID_ENUM, "the host's pending error is still its own after sky_draw (0x%04x)", e);

    sky_osmesa_make_current(&b);
    glEnable(0xBEEF);
    sky_result rc = sky_draw(checking, view, proj);
    NOTE("with checks: %s", sky_last_error(checking));
    CHECK(rc == SKY_ERR_GL && strstr(sky_last_error(checking), "pending before"),
          "with checks the host's error is named as pending before the call: %s", sky_last_error(checking));
    CHECK(sky_draw(checking, view, proj) == SKY_OK, "then the sky's own draw is clean: %s", sky_last_error(checking));

    /* a context of the host's own, without a sky */
    sky_osmesa other;
    if (sky_osmesa_create(&other, 32, 32, SKY_GL_AUTO, 0, err, sizeof err) == 0) {
        rc = sky_draw(plain, view, proj);
        NOTE("in a foreign context: %s", sky_last_error(plain));
        CHECK(rc == SKY_ERR_GL && strstr(sky_last_error(plain), "not the one"), "a foreign context is refused");
        sky_osmesa_destroy(&other);
    }
    sky_osmesa_release_current();
    rc = sky_draw(plain, view, proj);
    NOTE("with no context: %s", sky_last_error(plain));
    CHECK(rc == SKY_ERR_GL && strstr(sky_last_error(plain), "no GL context"), "no current context is refused");

    sky_osmesa_make_current(&a);
    sky_destroy(plain);
    sky_osmesa_destroy(&a);
    sky_osmesa_make_current(&b);
    sky_destroy(checking);
    sky_osmesa_destroy(&b);
}
