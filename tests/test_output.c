/*
 * sky-render's outputs (docs/guide.md, sky-render): an image reaches its path
 * whole or not at all, a failed write leaves the path as it was, a path
 * that is not a regular file is refused untouched, and any byte of an
 * image or of stdout not written is exit status 1.
 */
#include "test.h"

#include "osmesa_ctx.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <dirent.h>
#include <unistd.h>

/* A node with /dev/full's device numbers (every write: ENOSPC) at path;
 * 0 when made. Needs root: the tests skip without it. */
static int make_full_device(const char *path)
{
    char cmd[1024];
    unlink(path);
    snprintf(cmd, sizeof cmd, "mknod '%s' c 1 7 2>&1", path);
    return run_command(cmd, NULL, 0);
}

static int is_full_device(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISCHR(st.st_mode);
}

static int read_file(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
    fclose(f);
    return (int)n;
}

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int ok = fputs(text, f) >= 0;
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

/* Entries of dir other than . and .., so a temporary file left behind shows. */
static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

TEST(output_device_node_survives_failed_write)
{
    char render[512], pfm[512], png[512], cmd[2048], out[4096];
    bin_path("sky-render", render, sizeof render);
    tmp_path("full.pfm", pfm, sizeof pfm);
    tmp_path("full.png", png, sizeof png);
    if (make_full_device(pfm) || make_full_device(png)) {
        unlink(pfm);
        SKIP("mknod not permitted here");
        return;
    }
    snprintf(cmd, sizeof cmd, "%s --size 16x8 --out-pfm %s 2>&1", render, pfm);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 1, "--out-pfm at a device exits 1 (%d): %s", rc, out);
    CHECK(strstr(out, "not a regular file") != NULL, "the message says why: %s", out);
    CHECK(is_full_device(pfm), "the device node is still there");
    snprintf(cmd, sizeof cmd, "%s --size 16x8 --out %s 2>&1", render, png);
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 1, "--out at a device exits 1 (%d): %s", rc, out);
    CHECK(is_full_device(png), "the device node is still there");
    unlink(pfm);
    unlink(png);
}

TEST(output_directory_target_untouched)
{
    char render[512], dir[512], cmd[2048], out[4096];
    bin_path("sky-render", render, sizeof render);
    tmp_path("dir.png", dir, sizeof dir);
    rmdir(dir);
    CHECK(mkdir(dir, 0755) == 0, "mkdir %s", dir);
    snprintf(cmd, sizeof cmd, "%s --size 16x8 --out %s 2>&1", render, dir);
    int rc = run_command(cmd, out, sizeof out);
    struct stat st;
    CHECK(rc == 1, "--out at a directory exits 1 (%d): %s", rc, out);
    CHECK(strstr(out, "directory") != NULL, "the message says it is a directory: %s", out);
    CHECK(stat(dir, &st) == 0 && S_ISDIR(st.st_mode), "the empty directory is still there");
    CHECK(count_entries(dir) == 0, "and still empty");
    rmdir(dir);
}

/* A 64 KiB tmpfs: a PNG or PFM too big for it fails part way, as on a full
 * disk. The file already there keeps its contents and no temporary file is
 * left; an image that fits replaces it, keeping its permissions. */
TEST(output_full_disk_keeps_old_file)
{
    char render[512], dir[512], png[600], pfm[600], cmd[2048], out[4096], buf[256];
    bin_path("sky-render", render, sizeof render);
    tmp_path("tmpfs", dir, sizeof dir);
    mkdir(dir, 0755);
    snprintf(cmd, sizeof cmd, "mount -t tmpfs -o size=64k tmpfs '%s' 2>&1", dir);
    if (run_command(cmd, out, sizeof out) != 0) {
        rmdir(dir);
        SKIP("cannot mount a tmpfs here: %s", out);
        return;
    }
    snprintf(png, sizeof png, "%s/old.png", dir);
    snprintf(pfm, sizeof pfm, "%s/old.pfm", dir);
    CHECK(write_file(png, "old png") == 0 && write_file(pfm, "old pfm") == 0, "old files written");
    chmod(png, 0640);
    /* 512x512 with its dither noise is ~190 KB as PNG, 3 MB as PFM */
    snprintf(cmd, sizeof cmd, "%s --size 512x512 --preset overcast --out %s 2>&1", render, png);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 1, "a PNG bigger than the disk exits 1 (%d): %s", rc, out);
    CHECK(strstr(out, "No space left") != NULL, "the message says why: %s", out);
    CHECK(read_file(png, buf, sizeof buf) >= 0 && !strcmp(buf, "old png"), "old PNG kept: '%.20s'", buf);
    snprintf(cmd, sizeof cmd, "%s --size 512x512 --out-pfm %s 2>&1", render, pfm);
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 1, "a PFM bigger than the disk exits 1 (%d): %s", rc, out);
    CHECK(read_file(pfm, buf, sizeof buf) >= 0 && !strcmp(buf, "old pfm"), "old PFM kept: '%.20s'", buf);
    CHECK(count_entries(dir) == 2, "no temporary file left behind (%d entries)", count_entries(dir));
    /* one that fits replaces the old file */
    snprintf(cmd, sizeof cmd, "%s --size 32x16 --out %s 2>&1", render, png);
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "a small PNG fits (%d): %s", rc, out);
    image im;
    int loaded = image_load_png(png, &im) == 0;
    CHECK(loaded && im.w == 32 && im.h == 16, "the new PNG replaced the old file");
    if (loaded) image_free(&im);
    struct stat st;
    CHECK(stat(png, &st) == 0 && (st.st_mode & 0777) == 0640, "its permissions kept (%o)",
          (unsigned)(st.st_mode & 0777));
    CHECK(count_entries(dir) == 2, "no temporary file left behind (%d entries)", count_entries(dir));
    snprintf(cmd, sizeof cmd, "umount '%s' 2>&1", dir);
    CHECK(run_command(cmd, out, sizeof out) == 0, "umount: %s", out);
    rmdir(dir);
}

/* The encoder's sink itself, against a device where every write fails:
 * stbi_write_png alone reported success there. */
TEST(output_png_writer_checks_every_write)
{
    char dev[512];
    tmp_path("writer-full", dev, sizeof dev);
    if (make_full_device(dev)) {
        SKIP("mknod not permitted here");
        return;
    }
    unsigned char px[64 * 64 * 3];
    for (size_t i = 0; i < sizeof px; i++) px[i] = (unsigned char)(i * 7u);
    FILE *f = fopen(dev, "wb");
    CHECK(f != NULL, "open %s", dev);
    if (f) {
        errno = 0;
        int rc = sky_write_png_file(f, 64, 64, 3, px, 64 * 3);
        int e = errno;
        fclose(f);
        CHECK(rc == -1, "a PNG to a full device fails (%d)", rc);
        CHECK(e == ENOSPC, "with ENOSPC (%s)", strerror(e));
    }
    unlink(dev);
    /* and succeeds where there is room, with a PNG that reads back */
    f = tmpfile();
    CHECK(f != NULL, "tmpfile");
    if (f) {
        CHECK(sky_write_png_file(f, 64, 64, 3, px, 64 * 3) == 0, "a PNG to a file succeeds");
        long n = ftell(f);
        unsigned char sig[8] = {0};
        rewind(f);
        CHECK(n > 100 && fread(sig, 1, 8, f) == 8 && !memcmp(sig, "\x89PNG\r\n\x1a\n", 8), "a PNG (%ld bytes)", n);
        fclose(f);
    }
}

TEST(output_stdout_errors_exit_1)
{
    char render[512], dev[512], cmd[2048], out[4096];
    bin_path("sky-render", render, sizeof render);
    tmp_path("stdout-full", dev, sizeof dev);
    if (make_full_device(dev)) {
        SKIP("mknod not permitted here");
        return;
    }
    const char *args[] = {"--size 16x8 --stats", "--query", "--help"};
    for (size_t k = 0; k < sizeof args / sizeof args[0]; k++) {
        snprintf(cmd, sizeof cmd, "%s %s 2>&1 >%s", render, args[k], dev);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 1, "%s with stdout full exits 1 (%d): %s", args[k], rc, out);
        CHECK(strstr(out, "standard output") != NULL, "%s: the message says what failed: %s", args[k], out);
    }
    snprintf(cmd, sizeof cmd, "%s --query >/dev/null 2>&1", render);
    CHECK(run_command(cmd, out, sizeof out) == 0, "and exits 0 when stdout takes it");
    unlink(dev);
}

TEST(output_same_file_twice_rejected)
{
    char render[512], png[512], pfm[512], cmd[2048], out[4096], buf[64];
    bin_path("sky-render", render, sizeof render);
    tmp_path("same.png", png, sizeof png);
    tmp_path("same.pfm", pfm, sizeof pfm);
    for (int symbolic = 0; symbolic < 2; symbolic++) {
        unlink(png);
        unlink(pfm);
        CHECK(write_file(png, "untouched") == 0, "write %s", png);
        CHECK((symbolic ? symlink(png, pfm) : link(png, pfm)) == 0, "%s link", symbolic ? "symbolic" : "hard");
        snprintf(cmd, sizeof cmd, "%s --size 16x8 --out %s --out-pfm %s 2>&1", render, png, pfm);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 2, "%s link: exit 2 (%d): %s", symbolic ? "symbolic" : "hard", rc, out);
        CHECK(strstr(out, "--out ") && strstr(out, "--out-pfm") && strstr(out, "same file"),
              "the message names both options: %s", out);
        CHECK(read_file(png, buf, sizeof buf) >= 0 && !strcmp(buf, "untouched"), "nothing written");
    }
    unlink(png);
    unlink(pfm);
}
