/*
 * GL backend, asset files: a texture's file from the override directory
 * (cfg.texture_dir) or else the embedded copy, read with a hard size cap
 * and decoded to RGBA.
 */
/* open, fstat, O_NONBLOCK for the texture overrides (POSIX.1-2008) */
#if !defined(_WIN32) && !defined(_POSIX_C_SOURCE)
#define _POSIX_C_SOURCE 200809L
#endif
#include "gl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if !defined(_WIN32)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

/* Reads an override file with a hard size cap: hostile files never cause a
 * large allocation. Returns NULL if absent (no such name, or a dangling
 * symlink: both mean "no override"), or NULL with *failed set and a
 * message naming the file. */
static unsigned char *read_override(const char *dir, const char *name, size_t *size, char *err, size_t err_len,
                                    int *failed)
{
    enum { MAX_FILE = 16 << 20 };
    char path[1024];
    *failed = 0;
    if (!dir) return NULL;
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= sizeof path) {
        sky_format(err, err_len, "texture override path too long: %s/%s", dir, name);
        *failed = 1;
        return NULL;
    }
#if defined(_WIN32)
    FILE *f = fopen(path, "rb");
    if (!f) return NULL; /* no override for this one */
    unsigned char *buf = malloc(MAX_FILE);
    size_t got = buf ? fread(buf, 1, MAX_FILE, f) : 0;
    int too_big = buf && got == MAX_FILE && fgetc(f) != EOF;
    int read_error = ferror(f);
    fclose(f);
#else
    /* Non-blocking: opening a FIFO for reading otherwise waits for a
     * writer, which may never come (sky_create hung on one). Whatever is
     * not a regular file (FIFO, directory, device) is refused by fstat
     * before a byte is read. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        /* no file of that name: no override for this one; but a name that
         * is there and leads nowhere (a dangling symbolic link) was meant
         * as one, and is reported */
        struct stat link;
        if (errno == ENOENT && lstat(path, &link) == 0 && S_ISLNK(link.st_mode)) {
            sky_format(err, err_len, "%s: a symbolic link to a file that is missing", path);
            *failed = 1;
            return NULL;
        }
        if (errno == ENOENT || errno == ENOTDIR) return NULL;
        sky_format(err, err_len, "%s: cannot open: %s", path, strerror(errno));
        *failed = 1;
        return NULL;
    }
    struct stat st;
    int stat_failed = fstat(fd, &st) != 0;
    if (stat_failed || !S_ISREG(st.st_mode)) {
        sky_format(err, err_len, "%s: %s, not a PNG file", path,
                   stat_failed            ? "cannot be examined (fstat failed)"
                   : S_ISDIR(st.st_mode)  ? "a directory"
                   : S_ISFIFO(st.st_mode) ? "a FIFO"
                                          : "not a regular file");
        close(fd);
        *failed = 1;
        return NULL;
    }
    unsigned char *buf = st.st_size <= MAX_FILE ? malloc(MAX_FILE) : NULL;
    size_t got = 0;
    int too_big = st.st_size > MAX_FILE, read_error = 0;
    while (buf && got < MAX_FILE) {
        ssize_t r = read(fd, buf + got, MAX_FILE - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) read_error = 1;
        if (r <= 0) break;
        got += (size_t)r;
    }
    /* a file grown past the cap since fstat */
    unsigned char extra;
    if (buf && got == MAX_FILE && read(fd, &extra, 1) == 1) too_big = 1;
    close(fd);
#endif
    if (!buf || too_big || read_error || got == 0) {
        sky_format(err, err_len, "%s: %s", path,
                   too_big ? "larger than 16 MiB" : !buf ? "out of memory" : read_error ? "read error" : "empty file");
        free(buf);
        *failed = 1;
        return NULL;
    }
    *size = got;
    return buf;
}

int sky_asset_load_rgba(sky_core *s, const char *name, int expect_w, int expect_h, unsigned char **rgba_out, char *err,
                        size_t err_len)
{
    size_t size = 0;
    int failed = 0;
    *rgba_out = NULL;
    unsigned char *file = read_override(s->cfg.texture_dir, name, &size, err, err_len, &failed);
    if (failed) return -1;
    const unsigned char *data = file;
    if (!file) {
        const sky_blob *b = sky_find_blob(name);
        if (!b) {
            sky_format(err, err_len, "asset %s is not embedded in this build", name);
            return -1;
        }
        data = b->data;
        size = b->size;
    }
    char label[160];
    snprintf(label, sizeof label, "%s asset %s", file ? "override" : "embedded", name);
    int rc = sky_image_decode(data, size, expect_w, expect_h, rgba_out, label, err, err_len);
    free(file);
    return rc;
}
