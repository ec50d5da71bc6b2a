/*
 * pngcrop: the same region of several PNG frames side by side, at 1:1 or
 * enlarged by whole pixels (no filtering: what a player sees, pixel for
 * pixel), with a 4-pixel black gap between them. For the guide's
 * before/after pictures (tools/screenshots.sh).
 *
 *   pngcrop X,Y,W,H SCALE OUT.png IN.png...
 *
 * OUT is written to a new file beside it and renamed over it on success;
 * a frame smaller than the region is an error, not a padded picture.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

enum { GAP = 4, MAX_INPUTS = 12 };

typedef struct write_state {
    FILE *f;
    int failed;
} write_state;

/* stb's writer callback: a byte not written is an error */
static void write_bytes(void *context, void *data, int size)
{
    write_state *ws = context;
    if (size > 0 && fwrite(data, 1, (size_t)size, ws->f) != (size_t)size) ws->failed = 1;
}

static int usage(void)
{
    fprintf(stderr, "usage: pngcrop X,Y,W,H SCALE OUT.png IN.png... (1 to %d inputs, SCALE 1..8)\n", MAX_INPUTS);
    return 2;
}

int main(int argc, char **argv)
{
    int x0, y0, w, h, scale;
    char tail;
    if (argc < 5 || argc - 4 > MAX_INPUTS || sscanf(argv[1], "%d,%d,%d,%d%c", &x0, &y0, &w, &h, &tail) != 4 ||
        sscanf(argv[2], "%d%c", &scale, &tail) != 1 || x0 < 0 || y0 < 0 || w < 1 || h < 1 || w > 4096 ||
        h > 4096 || scale < 1 || scale > 8)
        return usage();
    int n = argc - 4, out_w = n * w * scale + (n - 1) * GAP, out_h = h * scale;
    unsigned char *out = calloc((size_t)out_w * (size_t)out_h, 3);
    if (!out) {
        fprintf(stderr, "pngcrop: out of memory\n");
        return 1;
    }
    for (int k = 0; k < n; k++) {
        int iw, ih, comp;
        unsigned char *in = stbi_load(argv[4 + k], &iw, &ih, &comp, 3);
        if (!in) {
            fprintf(stderr, "pngcrop: cannot read %s: %s\n", argv[4 + k], stbi_failure_reason());
            free(out);
            return 1;
        }
        if (x0 + w > iw || y0 + h > ih) {
            fprintf(stderr, "pngcrop: %d,%d,%d,%d is not inside %s (%dx%d)\n", x0, y0, w, h, argv[4 + k], iw, ih);
            stbi_image_free(in);
            free(out);
            return 1;
        }
        int left = k * (w * scale + GAP);
        for (int y = 0; y < out_h; y++)
            for (int x = 0; x < w * scale; x++)
                memcpy(out + 3 * ((size_t)y * out_w + left + x),
                       in + 3 * ((size_t)(y0 + y / scale) * iw + x0 + x / scale), 3);
        stbi_image_free(in);
    }
    /* a temporary file of our own beside OUT ("x": never one that exists) */
    size_t len = strlen(argv[3]);
    char *tmp = malloc(len + 16);
    FILE *f = NULL;
    for (int i = 0; tmp && !f && i < 100; i++) {
        snprintf(tmp, len + 16, "%s.%d.tmp", argv[3], i);
        f = fopen(tmp, "wbx");
    }
    if (!f) {
        fprintf(stderr, "pngcrop: cannot create a temporary file beside %s\n", argv[3]);
        free(out);
        free(tmp);
        return 1;
    }
    write_state ws = {f, 0};
    int ok = stbi_write_png_to_func(write_bytes, &ws, out_w, out_h, 3, out, out_w * 3) && !ws.failed;
    ok = fclose(f) == 0 && ok;
    free(out);
    if (!ok || rename(tmp, argv[3]) != 0) {
        fprintf(stderr, "pngcrop: cannot write %s: %s\n", argv[3], ok ? strerror(errno) : "a write failed");
        remove(tmp);
        free(tmp);
        return 1;
    }
    free(tmp);
    return 0;
}
