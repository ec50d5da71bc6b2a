/*
 * Sharpness of the 8-bit frame against the every-pixel frame (sharpness.h).
 */
#include "sharpness.h"

#include "cli.h"
#include "osmesa_ctx.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sky_sharpness_rows(int height) { return (int)((long)height * 460 / 720); }

double sky_fine_structure(const unsigned char *rgba, int width, int height, int rows, int k)
{
    size_t w1 = (size_t)width + 1;
    double *luma = malloc(sizeof(double) * (size_t)width * (size_t)height);
    double *sum = calloc(w1 * ((size_t)height + 1), sizeof(double)); /* summed-area table */
    if (!luma || !sum) {
        free(luma);
        free(sum);
        return -1.0;
    }
    for (size_t i = 0; i < (size_t)width * (size_t)height; i++)
        luma[i] = 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            sum[(y + 1) * w1 + x + 1] = luma[(size_t)y * width + x] + sum[y * w1 + x + 1] + sum[(y + 1) * w1 + x] -
                                        sum[y * w1 + x];
    /* the box of side 2k from k before the pixel, cut at the image's edges */
    double s1 = 0.0, s2 = 0.0;
    long n = 0;
    for (int y = 0; y < rows && y < height; y++)
        for (int x = 0; x < width; x++) {
            int x0 = x - k > 0 ? x - k : 0, y0 = y - k > 0 ? y - k : 0;
            int x1 = x + k < width ? x + k : width, y1 = y + k < height ? y + k : height;
            double box = (sum[y1 * w1 + x1] - sum[y0 * w1 + x1] - sum[y1 * w1 + x0] + sum[y0 * w1 + x0]) /
                         ((double)(x1 - x0) * (y1 - y0));
            double d = luma[(size_t)y * width + x] - box;
            s1 += d;
            s2 += d * d;
            n++;
        }
    free(luma);
    free(sum);
    if (!n) return 0.0;
    double mean = s1 / (double)n, var = s2 / (double)n - mean * mean;
    return sqrt(var > 0.0 ? var : 0.0);
}

double sky_psnr_rgba(const unsigned char *a, const unsigned char *b, int width, int height)
{
    double se = 0.0;
    size_t n = (size_t)width * (size_t)height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double d = (double)a[4 * i + c] - b[4 * i + c];
            se += d * d;
        }
    return se > 0.0 ? 10.0 * log10(255.0 * 255.0 * 3.0 * (double)n / se) : INFINITY;
}

int sky_sharpness_frame(const char *preset, const char *extra, int divisor, sky_gl_profile gl, int width, int height,
                        unsigned char **rgba, char *err, size_t err_len)
{
    *rgba = NULL;
    char words[256], div[8];
    snprintf(words, sizeof words, "%s", extra ? extra : "");
    snprintf(div, sizeof div, "%d", divisor);
    char *argv[16] = {"sky-sharpness", "--preset", (char *)preset};
    int argc = 3;
    if (divisor) argv[argc++] = "--dome-divisor", argv[argc++] = div;
    for (char *save = NULL, *t = strtok_r(words, " ", &save); t && argc < 15; t = strtok_r(NULL, " ", &save))
        argv[argc++] = t;
    argv[argc] = NULL;
    sky_cli cli;
    if (sky_cli_parse(&cli, argc, argv, 0, err, err_len)) return -1;
    cli.gl = gl;
    cli.width = width;
    cli.height = height;
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, width, height, gl, 0, err, err_len)) return -1;
    sky_config cfg = sky_cli_config(&cli, sky_headless_loader(&ctx));
    sky *s = sky_create(&cfg, err, err_len);
    int rc = -1;
    if (s && sky_set_params(s, &cli.params) >= 0 && sky_set_observer(s, &cli.observer) >= 0 &&
        sky_set_elapsed(s, cli.seconds) >= 0 && sky_set_exposure_bias(s, cli.exposure) >= 0) {
        float view[16], proj[16];
        sky_cli_camera(&cli, view, proj);
        if (sky_draw(s, view, proj) >= 0) {
            sky_osmesa_finish(&ctx);
            unsigned char *out = malloc((size_t)width * (size_t)height * 4);
            if (out) {
                const unsigned char *px = ctx.pixels; /* bottom row first */
                for (int y = 0; y < height; y++)
                    memcpy(out + (size_t)y * width * 4, px + (size_t)(height - 1 - y) * width * 4, (size_t)width * 4);
                *rgba = out;
                rc = 0;
            } else
                snprintf(err, err_len, "out of memory for a %dx%d frame", width, height);
        }
    }
    if (s && rc) snprintf(err, err_len, "%s", sky_last_error(s));
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

int sky_sharpness_measure(const char *preset, const char *extra, sky_gl_profile gl, int width, int height,
                          sky_sharpness *out, char *err, size_t err_len)
{
    unsigned char *def = NULL, *every = NULL;
    int rc = -1;
    if (!sky_sharpness_frame(preset, extra, 0, gl, width, height, &def, err, err_len) &&
        !sky_sharpness_frame(preset, extra, 1, gl, width, height, &every, err, err_len)) {
        int rows = sky_sharpness_rows(height);
        double f[2][2]; /* [frame][k = 2, 5] */
        for (int i = 0; i < 2; i++) {
            f[0][i] = sky_fine_structure(def, width, height, rows, i ? 5 : 2);
            f[1][i] = sky_fine_structure(every, width, height, rows, i ? 5 : 2);
        }
        if (f[0][0] < 0.0 || f[0][1] < 0.0 || f[1][0] < 0.0 || f[1][1] < 0.0)
            snprintf(err, err_len, "out of memory measuring a %dx%d frame", width, height);
        else {
            out->kept2 = f[1][0] > 0.0 ? f[0][0] / f[1][0] : 1.0;
            out->kept5 = f[1][1] > 0.0 ? f[0][1] / f[1][1] : 1.0;
            out->psnr = sky_psnr_rgba(every, def, width, height);
            rc = 0;
        }
    }
    free(def);
    free(every);
    return rc;
}
