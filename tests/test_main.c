/*
 * libsky's test runner: runs every test (or those whose name contains
 * argv[1]) and ends with the line "N passed, N failed" (followed by
 * ", N skipped" when a test could not run here).
 */
#include "test.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* The test program's own PNG reader (the library keeps its copy private). */
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

int test_failures;
int test_skipped;

#if defined(SKY_WEB_TESTS)
/* the browser build's runner (make test-web): tests/web/ */
#define TESTS(X)                        \
    X(web_page_shows_a_sky)             \
    X(web_drag_changes_the_frame)       \
    X(web_preset_switch)
#elif defined(SKY_EXAMPLE_TESTS)
/* the engine examples' runner (make test-examples): the same harness, its
 * own tests (tests/examples/) */
#define TESTS(X)                                 \
    X(examples_sdl2_sky_above_scene_below)       \
    X(examples_osg_sky_above_scene_below)        \
    X(examples_irrlicht_sky_above_scene_below)   \
    X(examples_sdl2_sun_where_lighting_says)     \
    X(examples_osg_sun_where_lighting_says)      \
    X(examples_irrlicht_sun_where_lighting_says) \
    X(examples_irrlicht_left_handed)             \
    X(examples_sdl2_depth_conventions)
#else
#define TESTS(X)                                 \
    X(api_zero_config_renders)                   \
    X(api_rejects_null_and_bad_config)           \
    X(api_sliders_clamp_and_reject_nan)          \
    X(api_update_time_validation)                \
    X(api_draw_rejects_bad_matrices)             \
    X(api_lighting_and_stats)                    \
    X(api_gl_objects_deleted)                    \
    X(api_leaks_1000_cycles)                     \
    X(gl_state_restored_core)                    \
    X(gl_state_restored_compat)                  \
    X(es20_state_restored)                       \
    X(es20_profile_mismatch_is_an_error)         \
    X(es20_aerial_snippet)                       \
    X(es20_capture_cross)                        \
    X(es20_mediump_fragment_stage)               \
    X(es20_presets_match_compat20)               \
    X(es20_without_optional_extensions)          \
    X(es20_every_path_with_every_layer)          \
    X(gl_host_raster_state_ignored)              \
    X(gl_errors_left_to_host_and_contexts_checked) \
    X(header_compiles_pedantic)                  \
    X(conventions_left_handed_host)              \
    X(conventions_version_everywhere)            \
    X(conventions_sky_after_the_scene)           \
    X(validation_dates)                          \
    X(validation_config_fields_named)            \
    X(validation_extreme_aspect_ratio)           \
    X(validation_ldr_in_float_target_stays_in_range) \
    X(render_cover_zero_has_no_clouds)           \
    X(render_full_cover_hides_sky)               \
    X(render_density_darkens_clouds)             \
    X(render_day_bright_night_dark_with_stars)   \
    X(render_no_star_work_at_noon)               \
    X(render_flicker_changes_with_seconds)       \
    X(render_clouds_drift_by_expected_offset)    \
    X(render_drift_stays_smooth_after_years)     \
    X(render_height_changes_cloud_scale)         \
    X(render_sun_where_direction_projects)       \
    X(render_sun_in_fisheye)                     \
    X(render_sun_disc_sums_to_sunlight)          \
    X(render_hdr_finite_everywhere)              \
    X(render_dome_image_agrees_with_every_pixel) \
    X(render_dome_covers_every_view)             \
    X(colour_hue_and_saturation_kept)            \
    X(colour_old_curve_fails_the_measure)        \
    X(colour_one_ground_below_the_horizon)       \
    X(colour_noon_as_bright_as_before)           \
    X(colour_day_ends_darker)                    \
    X(colour_exposure_range_spares_noon)         \
    X(colour_night_is_blue)                      \
    X(display_glsl_matches_ldr)                  \
    X(display_bind_checks)                       \
    X(profiles_core_and_compat_agree)            \
    X(profiles_compat_on_emulated_2004_gpu)      \
    X(profiles_every_path_with_every_layer)      \
    X(profiles_too_old_context_is_an_error)      \
    X(texture_budget_minimal_path)               \
    X(textures_tile_without_seams)               \
    X(flicker_texture_neighbourhoods)            \
    X(cli_exit_codes_and_messages)               \
    X(cli_every_option_checked)                  \
    X(cli_screenshot_must_be_png)                \
    X(cli_no_output_says_so)                     \
    X(cli_help_exits_0)                          \
    X(cli_demo_help_lists_every_key)             \
    X(output_device_node_survives_failed_write)  \
    X(output_directory_target_untouched)         \
    X(output_full_disk_keeps_old_file)           \
    X(output_png_writer_checks_every_write)      \
    X(output_stdout_errors_exit_1)               \
    X(output_same_file_twice_rejected)           \
    X(docs_no_paths_outside_the_repository)      \
    X(docs_readme_figures_agree)                 \
    X(astro_time_scales)                         \
    X(astro_sun_vs_erfa)                         \
    X(astro_moon_vs_erfa)                        \
    X(astro_stars_vs_erfa)                       \
    X(astro_phase_and_eclipse_vs_erfa)           \
    X(astro_historic_lunar_eclipses)             \
    X(astro_refraction)                          \
    X(astro_solar_eclipse_totality)              \
    X(astro_solar_eclipse_partial_vs_erfa)       \
    X(render_total_solar_eclipse)                \
    X(astro_bad_input)                           \
    X(astro_node_cache)                          \
    X(astro_time_slider_is_solar_time)           \
    X(astro_query_json)                          \
    X(planets_vs_pyephem)                        \
    X(planets_magnitudes_published)              \
    X(planets_state_serves_its_window)           \
    X(planets_drawn_where_astronomy_puts_them)   \
    X(planets_light_sums_to_magnitude)           \
    X(planets_venus_in_the_afternoon)            \
    X(planets_layer_costs)                       \
    X(planets_layer_follows_the_clock)           \
    X(nightglow_dark_site_zenith)                \
    X(nightglow_bortle_classes)                  \
    X(nightglow_zodiacal_follows_the_table)      \
    X(nightglow_cpu_matches_render)              \
    X(nightglow_layer_costs)                     \
    X(nightglow_naked_eye_limit)                 \
    X(stars_where_astronomy_puts_them)           \
    X(stars_control_magnitude_and_twilight)      \
    X(stars_colour_follows_bv)                   \
    X(stars_scintillate_more_near_horizon)       \
    X(stars_skipped_at_noon)                     \
    X(stars_flux_with_and_without_glare)         \
    X(stars_cells_lose_no_star)                  \
    X(starmap_shows_the_milky_way)               \
    X(moon_phase_and_bright_limb)                \
    X(moon_earthshine_on_a_crescent)             \
    X(moon_total_eclipse_is_dark_and_red)        \
    X(moon_penumbral_eclipse_is_slightly_darker) \
    X(moon_left_out_when_not_needed)             \
    X(moon_rising_is_flattened)                  \
    X(moon_hides_the_stars_behind_it)            \
    X(moon_disc_sums_to_moonlight)               \
    X(moon_scale_keeps_luminance)                \
    X(demo_window_shows_sky_and_sliders)         \
    X(demo_drag_on_cover_slider)                 \
    X(demo_readout_is_gpu_frame_time)            \
    X(bench_preset_table_in_rounds)              \
    X(bench_rejects_bad_rounds)                  \
    X(bench_es20_presets)                        \
    X(sharpness_measure_properties)              \
    X(sharpness_day_clouds_kept)                 \
    X(game_lit_by_the_sky)                       \
    X(headless_frames_are_rendered)              \
    X(headless_demo_writes_where_asked)          \
    X(unwritable_screenshot_fails)               \
    X(game_compat_context)                       \
    X(game_options_are_its_own)                  \
    X(game_fog_grows_with_distance)              \
    X(game_walls_seen_at_night)                  \
    X(demo_rebuild_keeps_the_clock)              \
    X(demo_atmosphere_key)                       \
    X(demo_es20_window)                          \
    X(headless_out_must_be_png)                  \
    X(reliability_hostile_override_textures)     \
    X(reliability_two_skies_are_independent)     \
    X(reliability_soak_10000_frames)             \
    X(hostile_missing_gl_entry_point)            \
    X(hostile_context_lost)                      \
    X(hostile_fifo_override)                     \
    X(hostile_directory_override)                \
    X(hostile_palette_overrun)                   \
    X(hostile_core_context_names_what_it_lacks)  \
    X(atmosphere_paths_finite_for_every_sun_position) \
    X(atmosphere_clear_sky_colours)              \
    X(atmosphere_shaders_match_cpu_twins)        \
    X(atmosphere_moonlit_sky)                    \
    X(atmosphere_clouds_lit_by_moon)             \
    X(atmosphere_moonlight_reaches_the_host)     \
    X(atmosphere_continuous_across_horizon)      \
    X(atmosphere_preetham_outside_its_fit)       \
    X(atmosphere_description_checked)            \
    X(atmosphere_error_against_reference)        \
    X(atmosphere_gpu_tables_match_cpu)           \
    X(atmosphere_extinction_follows_the_description) \
    X(atmosphere_observer_altitudes)             \
    X(atmosphere_setting_sun_flattened)          \
    X(atmosphere_turbidity_and_presets)          \
    X(atmosphere_blend_partner_preetham)         \
    X(stability_suite)                           \
    X(stability_suite_es20)                      \
    X(stability_clocks_survive_any_step)         \
    X(reference_spectrum_and_units)              \
    X(reference_single_scattering_vs_quadrature) \
    X(reference_energy_balance)                  \
    X(reference_converges)                       \
    X(reference_sky_is_plausible)                \
    X(hillaire_transmittance_table)              \
    X(hillaire_sky_vs_reference)                 \
    X(hillaire_error_falls_with_table_size)      \
    X(hillaire_finite_everywhere)                \
    X(hillaire_rebuilds_identical)               \
    X(hillaire_bad_input)                        \
    X(hillaire_timelapse_under_1ms_a_frame)      \
    X(hillaire_timelapse_shows_whole_tables)     \
    X(hillaire_timelapse_settles_on_exact_table) \
    X(hillaire_jump_builds_at_once)              \
    X(cli_outputs_png_pfm_stats)                 \
    X(photometry_published_formulas)             \
    X(photometry_measures_every_path)            \
    X(photometry_preetham_twilight)              \
    X(photometry_physical_paths_targets)         \
    X(photometry_rayleigh_goes_dark)             \
    X(lighting_sh_irradiance_matches_render)     \
    X(lighting_sh_checks_its_input)              \
    X(lighting_sh_with_clouds)                   \
    X(lighting_sh_matches_fisheye)               \
    X(lighting_sh_in_the_world_frame)            \
    X(lighting_capture_faces_are_sky_draw)       \
    X(lighting_capture_checks_and_restores)      \
    X(lighting_capture_hdr)                      \
    X(lighting_capture_without_framebuffer_objects) \
    X(aerial_meets_the_sky)                      \
    X(aerial_against_reference)                  \
    X(aerial_checks_its_input)                   \
    X(aerial_glsl_matches_cpu)                   \
    X(aerial_froxels_match_cpu)
#endif

#define DECLARE(name) void test_##name(void);
TESTS(DECLARE)
#undef DECLARE

/* ---- fixtures ------------------------------------------------------------- */

scene scene_default(void)
{
    scene sc;
    memset(&sc, 0, sizeof sc);
    sc.params = sky_default_params();
    sc.yaw = 180.0;
    sc.pitch = 20.0;
    sc.fov = 60.0;
    sc.w = 320;
    sc.h = 180;
    return sc;
}

void scene_camera(const scene *sc, float view[16], float proj[16])
{
    sky_cli_camera_at(sc->yaw, sc->pitch, sc->fov, sc->w, sc->h, view, proj);
}

int scene_project(const scene *sc, double alt_deg, double az_deg, double *px, double *py)
{
    const double deg = 3.14159265358979323846 / 180.0;
    float view[16], proj[16];
    scene_camera(sc, view, proj);
    double d[3] = {cos(alt_deg * deg) * sin(az_deg * deg), sin(alt_deg * deg), -cos(alt_deg * deg) * cos(az_deg * deg)};
    double e[4], c[4];
    for (int r = 0; r < 4; r++) e[r] = view[r] * d[0] + view[4 + r] * d[1] + view[8 + r] * d[2];
    for (int r = 0; r < 4; r++) c[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2];
    if (c[3] <= 0.0) return -1;
    *px = (c[0] / c[3] + 1.0) * 0.5 * sc->w;
    *py = (1.0 - c[1] / c[3]) * 0.5 * sc->h;
    return 0;
}

double image_blob(const image *im, double cx, double cy, int r, double *bx, double *by)
{
    double peak = 0.0;
    for (int y = (int)cy - r; y <= (int)cy + r; y++)
        for (int x = (int)cx - r; x <= (int)cx + r; x++)
            if (x >= 0 && y >= 0 && x < im->w && y < im->h) peak = fmax(peak, image_luminance(im, x, y));
    double sx = 0, sy = 0, sw = 0;
    for (int y = (int)cy - r; y <= (int)cy + r; y++)
        for (int x = (int)cx - r; x <= (int)cx + r; x++)
            if (x >= 0 && y >= 0 && x < im->w && y < im->h) {
                double l = image_luminance(im, x, y);
                if (l > 0.3 * peak) sx += l * (x + 0.5), sy += l * (y + 0.5), sw += l;
            }
    *bx = sw > 0 ? sx / sw : -1;
    *by = sw > 0 ? sy / sw : -1;
    return peak;
}

double image_centre_sum(const float *rgba, int n, int radius)
{
    double ring[2048];
    int nr = 0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            double r = hypot(x + 0.5 - n / 2.0, y + 0.5 - n / 2.0);
            if (r > radius + 2 && r <= radius + 6 && nr < 2048) {
                const float *q = rgba + 4 * (y * n + x);
                ring[nr++] = 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
            }
        }
    for (int i = 1; i < nr; i++) /* insertion sort: a few hundred values */
        for (int j = i; j > 0 && ring[j] < ring[j - 1]; j--) {
            double t = ring[j];
            ring[j] = ring[j - 1], ring[j - 1] = t;
        }
    double bg = nr ? ring[nr / 2] : 0.0, sum = 0.0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++)
            if (hypot(x + 0.5 - n / 2.0, y + 0.5 - n / 2.0) <= radius) {
                const float *q = rgba + 4 * (y * n + x);
                sum += 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2] - bg;
            }
    return sum;
}

int render_scene(const scene *sc, int hdr, sky_gl_profile want, image *out)
{
    char err[512];
    sky_osmesa ctx;
    memset(out, 0, sizeof *out);
    sky_gl_profile ctx_kind = want == SKY_GL_COMPAT20 ? SKY_GL_COMPAT20 : want;
    if (sky_osmesa_create(&ctx, sc->w, sc->h, ctx_kind, hdr, err, sizeof err)) {
        printf("    render_scene: %s\n", err);
        return -1;
    }
    sky_config cfg = sc->cfg;
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.output = hdr ? SKY_OUTPUT_HDR : SKY_OUTPUT_LDR;
    cfg.gl_profile = want;
    cfg.check_gl_errors = 1; /* the tests want every GL error the sky makes */
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        printf("    render_scene: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return -1;
    }
    int rc = 0;
    if (sky_set_params(s, &sc->params) < 0 || sky_set_elapsed(s, sc->seconds) < 0 ||
        (sc->has_observer && sky_set_observer(s, &sc->observer) != SKY_OK) ||
        sky_set_exposure_bias(s, sc->exposure_bias) != SKY_OK)
        rc = -1;
    float view[16], proj[16];
    scene_camera(sc, view, proj);
    if (!rc && (sc->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) < 0) {
        printf("    render_scene: %s\n", sky_last_error(s));
        rc = -1;
    }
    sky_osmesa_finish(&ctx);
    if (!rc) {
        out->w = sc->w;
        out->h = sc->h;
        out->px = malloc(sizeof(float) * 3u * (size_t)sc->w * (size_t)sc->h);
        for (int y = 0; y < sc->h; y++)
            for (int x = 0; x < sc->w; x++)
                for (int c = 0; c < 3; c++) {
                    size_t src = ((size_t)(sc->h - 1 - y) * (size_t)sc->w + (size_t)x) * 4u + (size_t)c;
                    float v = hdr ? ((const float *)ctx.pixels)[src] : ((const unsigned char *)ctx.pixels)[src] / 255.0f;
                    out->px[((size_t)y * (size_t)sc->w + (size_t)x) * 3u + (size_t)c] = v;
                }
    }
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

int fixture_open(fixture *f, sky_gl_profile profile, const sky_config *base)
{
    return fixture_open_sized(f, 64, 48, 0, profile, base);
}

sky_observer equator_equinox(void)
{
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.julian_day_utc = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    o.time_from_params = 1;
    return o;
}

int fixture_open_sized(fixture *f, int w, int h, int float_buffer, sky_gl_profile profile, const sky_config *base)
{
    char err[512];
    memset(f, 0, sizeof *f);
    if (sky_osmesa_create(&f->ctx, w, h, profile, float_buffer, err, sizeof err)) {
        printf("    %s\n", err);
        return -1;
    }
    sky_config cfg;
    if (base)
        cfg = *base;
    else
        memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.gl_profile = profile;
    cfg.check_gl_errors = 1; /* the tests want every GL error the sky makes */
    f->s = sky_create(&cfg, err, sizeof err);
    if (!f->s) {
        printf("    sky_create: %s\n", err);
        sky_osmesa_destroy(&f->ctx);
        return -1;
    }
    return 0;
}

void fixture_close(fixture *f)
{
    sky_destroy(f->s);
    sky_osmesa_destroy(&f->ctx);
}

void image_free(image *im)
{
    free(im->px);
    im->px = NULL;
}

float image_luminance(const image *im, int x, int y)
{
    const float *p = im->px + ((size_t)y * (size_t)im->w + (size_t)x) * 3u;
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

int image_load_png(const char *path, image *out)
{
    int w, h, n;
    memset(out, 0, sizeof *out);
    unsigned char *p = stbi_load(path, &w, &h, &n, 3);
    if (!p) return -1;
    out->w = w;
    out->h = h;
    out->px = malloc(sizeof(float) * 3u * (size_t)w * (size_t)h);
    for (size_t i = 0; i < 3u * (size_t)w * (size_t)h; i++) out->px[i] = p[i] / 255.0f;
    stbi_image_free(p);
    return 0;
}

const char *bin_path(const char *name, char *buf, size_t len)
{
    const char *dir = getenv("SKY_BIN");
    snprintf(buf, len, "%s/%s", dir ? dir : "build/bin", name);
    return buf;
}

const char *tmp_path(const char *name, char *buf, size_t len)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, len, "%s/sky-test-%d-%s", dir ? dir : "/tmp", (int)getpid(), name);
    return buf;
}

int run_command(const char *cmd, char *buf, size_t len)
{
    FILE *p = popen(cmd, "r");
    if (!p) return -1;
    size_t used = 0;
    if (buf && len) buf[0] = '\0';
    char chunk[512];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, p)) > 0)
        if (buf && used + 1 < len) {
            size_t k = n < len - 1 - used ? n : len - 1 - used;
            memcpy(buf + used, chunk, k);
            used += k;
            buf[used] = '\0';
        }
    int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* ---- runner ----------------------------------------------------------------- */

int main(int argc, char **argv)
{
    static const test_case tests[] = {
#define ENTRY(name) {#name, test_##name},
        TESTS(ENTRY)
#undef ENTRY
    };
    setvbuf(stdout, NULL, _IOLBF, 0);
    int passed = 0, failed = 0, skipped = 0;
    for (size_t i = 0; i < sizeof tests / sizeof tests[0]; i++) {
        if (argc > 1 && !strstr(tests[i].name, argv[1])) continue;
        test_failures = 0;
        test_skipped = 0;
        printf("  %s\n", tests[i].name);
        tests[i].fn();
        if (test_failures) {
            printf("FAIL %s\n", tests[i].name);
            failed++;
        } else if (test_skipped) {
            printf("skip %s\n", tests[i].name);
            skipped++;
        } else {
            printf("ok   %s\n", tests[i].name);
            passed++;
        }
    }
    /* the skip count only when there is one, so a complete run ends with
     * exactly "N passed, N failed" */
    if (skipped) printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    else printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
