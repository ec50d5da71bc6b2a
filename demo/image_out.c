/* The image files sky-render and the tests write (osmesa_ctx.h): every
 * byte checked, written beside the target and renamed over it. Portable
 * C with POSIX files, and Windows' equivalents where they differ. */
#include "osmesa_ctx.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#ifdef _WIN32
#include <io.h>
#include <process.h>
#include <windows.h>
#else
#include <unistd.h>
#endif

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* ---- output files ------------------------------------------------------
 * A file is written beside its target under a unique temporary name and
 * renamed over the target only once every byte has been written, flushed
 * and synced: a failed write then leaves whatever the target was (an older
 * image, nothing) as it was, and the only thing ever deleted is our own
 * temporary file. Deleting the path itself on failure, as before, removed
 * whatever the user had named - a device node, an empty directory.
 * A target that exists and is not a regular file (a directory, a device
 * such as /dev/null, a FIFO) is refused untouched: renaming over it would
 * replace it, and writing into it in place would give up the guarantee. */

#ifdef _WIN32
#define OPEN_BINARY O_BINARY
static int sync_file(int fd) { return _commit(fd); }
/* rename refuses an existing target on Windows; MoveFileEx replaces it
 * (and, like rename, either moves the whole file or nothing) */
static int replace_file(const char *from, const char *to)
{
    if (MoveFileExA(from, to, MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return 0;
    errno = GetLastError() == ERROR_ACCESS_DENIED ? EACCES : EIO;
    return -1;
}
#else
#define OPEN_BINARY 0
static int sync_file(int fd) { return fsync(fd); }
static int replace_file(const char *from, const char *to) { return rename(from, to); }
#endif

static void set_err(char *err, size_t len, const char *fmt, const char *path, const char *why)
{
    if (err && len) snprintf(err, len, fmt, path, why);
}

typedef struct out_file {
    FILE *f;
    char tmp[4096];
    const char *path;
} out_file;

static int out_open(out_file *o, const char *path, char *err, size_t len)
{
    memset(o, 0, sizeof *o);
    o->path = path;
    struct stat st;
    int exists = stat(path, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        set_err(err, len, "%s: %s", path,
                S_ISDIR(st.st_mode) ? "is a directory (left untouched)"
                                    : "exists and is not a regular file (left untouched; only regular files are "
                                      "written)");
        return -1;
    }
    const char *slash = strrchr(path, '/');
    int dir_len = slash ? (int)(slash - path) + 1 : 0;
    int fd = -1;
    /* O_EXCL rather than mkstemp: open's 0666 goes through the umask as
     * any new file's mode would, where mkstemp's 0600 would not */
    for (int n = 0; fd < 0 && n < 100; n++) {
        int w = snprintf(o->tmp, sizeof o->tmp, "%.*s.%s.%ld-%d.tmp", dir_len, path, path + dir_len,
                         (long)getpid(), n);
        if (w < 0 || (size_t)w >= sizeof o->tmp) {
            set_err(err, len, "%s: %s", path, "path too long");
            return -1;
        }
        fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL | OPEN_BINARY, 0666);
        if (fd < 0 && errno != EEXIST) {
            set_err(err, len, "%s: %s", path, strerror(errno));
            return -1;
        }
    }
    if (fd < 0) {
        set_err(err, len, "%s: %s", path, "no free temporary name beside it");
        return -1;
    }
#ifndef _WIN32
    /* replacing a file keeps its permissions (Windows' read-only bit
     * would refuse the rename, which then says so) */
    if (exists) (void)fchmod(fd, st.st_mode & 07777);
#endif
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        set_err(err, len, "%s: %s", path, strerror(errno));
        close(fd);
        unlink(o->tmp);
        return -1;
    }
    return 0;
}

/* ok: whether every write so far succeeded (errno then says why not).
 * Flushes, syncs and closes; renames into place, or removes the temporary
 * file. Returns 0 or -1 with err. */
static int out_close(out_file *o, int ok, char *err, size_t len)
{
    int e = ok ? 0 : errno;
    if (fflush(o->f) != 0 && ok) ok = 0, e = errno;
    /* fsync: some file systems report a full disk only here, and a rename
     * of a file whose data is not yet on disk can leave an empty target
     * after a crash */
    if (ok && sync_file(fileno(o->f)) != 0) ok = 0, e = errno;
    if (fclose(o->f) != 0 && ok) ok = 0, e = errno;
    o->f = NULL;
    if (ok && replace_file(o->tmp, o->path) != 0) ok = 0, e = errno;
    if (!ok) {
        unlink(o->tmp);
        set_err(err, len, "%s: %s", o->path, e ? strerror(e) : "write failed");
        return -1;
    }
    return 0;
}

/* stbi_write_png itself ignores fwrite's and fclose's results, so a full
 * disk left a truncated PNG and a success: the encoder writes through this
 * sink instead, which remembers the first failure. */
typedef struct png_sink {
    FILE *f;
    int failed, err;
} png_sink;

static void png_sink_write(void *ctx, void *data, int size)
{
    png_sink *s = ctx;
    if (s->failed || size <= 0) return;
    if (fwrite(data, 1, (size_t)size, s->f) != (size_t)size) {
        s->failed = 1;
        s->err = errno;
    }
}

int sky_write_png_file(FILE *f, int width, int height, int comp, const unsigned char *px, int stride)
{
    png_sink s = {f, 0, 0};
    if (!stbi_write_png_to_func(png_sink_write, &s, width, height, comp, px, stride)) {
        errno = ENOMEM; /* the encoder's only failure is an allocation */
        return -1;
    }
    if (!s.failed && fflush(f) != 0) s.failed = 1, s.err = errno;
    if (s.failed) {
        errno = s.err ? s.err : EIO;
        return -1;
    }
    return 0;
}

static int write_png_path(const char *path, int width, int height, int comp, const unsigned char *px, int stride,
                          char *err, size_t len)
{
    out_file o;
    if (out_open(&o, path, err, len)) return -1;
    int ok = sky_write_png_file(o.f, width, height, comp, px, stride) == 0;
    return out_close(&o, ok, err, len);
}

int sky_osmesa_write_png(const sky_osmesa *o, const char *path, char *err, size_t err_len)
{
    size_t row = (size_t)o->width * 4u;
    unsigned char *img = malloc(row * (size_t)o->height);
    if (!img) {
        set_err(err, err_len, "%s: %s", path, "out of memory");
        return -1;
    }
    for (int y = 0; y < o->height; y++) {
        unsigned char *dst = img + row * (size_t)(o->height - 1 - y);
        if (o->is_float) {
            const float *src = (const float *)o->pixels + (size_t)y * row;
            for (size_t i = 0; i < row; i++) {
                float v = src[i] < 0.0f ? 0.0f : src[i] > 1.0f ? 1.0f : src[i];
                dst[i] = (unsigned char)(v * 255.0f + 0.5f);
            }
        } else {
            memcpy(dst, (const unsigned char *)o->pixels + (size_t)y * row, row);
        }
        for (int x = 0; x < o->width; x++) dst[4 * x + 3] = 255; /* opaque */
    }
    int rc = write_png_path(path, o->width, o->height, 4, img, (int)row, err, err_len);
    free(img);
    return rc;
}

int sky_osmesa_write_pfm(const sky_osmesa *o, const char *path, char *err, size_t err_len)
{
    if (!o->is_float) {
        set_err(err, err_len, "%s: %s", path, "not a float buffer");
        return -1;
    }
    out_file out;
    if (out_open(&out, path, err, err_len)) return -1;
    FILE *f = out.f;
    /* floats are written natively; the sign of the scale says which byte
     * order that is (negative = little endian) */
    const float one = 1.0f;
    unsigned char first_byte;
    memcpy(&first_byte, &one, 1);
    int ok = fprintf(f, "PF\n%d %d\n%s\n", o->width, o->height, first_byte == 0 ? "-1.0" : "1.0") > 0;
    const float *px = o->pixels;
    for (int y = 0; ok && y < o->height; y++)
        for (int x = 0; ok && x < o->width; x++) {
            const float *p = px + ((size_t)y * (size_t)o->width + (size_t)x) * 4u;
            ok = fwrite(p, sizeof(float), 3, f) == 3;
        }
    return out_close(&out, ok, err, err_len);
}

int sky_write_png_rgb(const char *path, int width, int height, const unsigned char *rgb)
{
    if (!path || !rgb || width <= 0 || height <= 0) return -1;
    return write_png_path(path, width, height, 3, rgb, width * 3, NULL, 0);
}
