/*
 * The library as other projects take it: CMakeLists.txt installed and
 * found (find_package), built inside a host's tree (add_subdirectory), the
 * installed sky.pc, and README.md's "Use it in your build" run as written.
 * Each test works in a temporary directory of its own (tmp_path) and
 * removes it; the consumers are tests/cmake/.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A fresh directory for a test: tmp_path's name plus mkdtemp's suffix.
 * Returns 0, or -1 after a failed CHECK. */
static int temp_dir(const char *name, char *dir, size_t len)
{
    char base[400];
    tmp_path(name, base, sizeof base);
    snprintf(dir, len, "%s-XXXXXX", base);
    int ok = mkdtemp(dir) != NULL;
    CHECK(ok, "a temporary directory %s", dir);
    return ok ? 0 : -1;
}

/* Removes what temp_dir made, and nothing else: the name must be one of
 * tmp_path's. */
static void remove_temp_dir(const char *dir)
{
    char base[400], cmd[1200], out[256];
    tmp_path("", base, sizeof base);
    if (strncmp(dir, base, strlen(base)) != 0 || strchr(dir, '\'')) return;
    snprintf(cmd, sizeof cmd, "rm -rf '%s' 2>&1", dir);
    run_command(cmd, out, sizeof out);
}

/* Whether a shell command is there (cmake, clang, pkg-config). */
static int have(const char *program)
{
    char cmd[200], out[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", program);
    return run_command(cmd, out, sizeof out) == 0;
}

static int file_exists(const char *dir, const char *name)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

/* Runs a command whose output is long (a build): into LOG, and on
 * failure its last lines into out. Returns the exit status. */
static int run_logged(const char *cmd, const char *log, char *out, size_t len)
{
    static char full[16384];
    snprintf(full, sizeof full, "{ %s ; } > '%s' 2>&1; rc=$?; [ $rc = 0 ] || tail -n 25 '%s'; exit $rc", cmd, log,
             log);
    return run_command(full, out, len);
}

/* What tests/cmake/consumer.c prints: the library's version, the header's,
 * and the sun at Greenwich's solstice noon near 62 degrees up. */
static void check_consumer_output(const char *how, const char *out)
{
    char want[64];
    snprintf(want, sizeof want, "sky %d.%d.%d\n", SKY_VERSION_MAJOR, SKY_VERSION_MINOR, SKY_VERSION_PATCH);
    CHECK(strncmp(out, want, strlen(want)) == 0, "%s: the consumer linked libsky %.*s: %.300s", how,
          (int)strlen(want) - 1, want, out);
    const char *sun = strstr(out, "sun at ");
    double alt = sun ? atof(sun + 7) : -99.0;
    CHECK(alt > 61.0 && alt < 63.0, "%s: the sun at %.2f degrees (61..63 expected): %.300s", how, alt, out);
}

/* The soname's version part: 0.MINOR before 1.0, MAJOR after (sky.h). */
static void soname_of(char *buf, size_t len)
{
    if (SKY_VERSION_MAJOR == 0) snprintf(buf, len, "libsky.so.0.%d", SKY_VERSION_MINOR);
    else snprintf(buf, len, "libsky.so.%d", SKY_VERSION_MAJOR);
}

/* libsky configured, built (warnings as errors) and installed through
 * CMake into a temporary prefix, static and shared: the install holds
 * sky.h, the library under its soname, sky.pc and the package; the shared
 * library exports exactly sky.h's SKY_API functions, all named sky_;
 * tests/cmake/find_package finds it (asking for sky.h's MAJOR.MINOR),
 * builds and runs, as does the consumer compiled against the installed
 * sky.pc (pkg-config --static for the static prefix, which holds libsky.a
 * alone), and cmake --install --prefix writes a sky.pc naming its prefix;
 * and before 1.0 the package refuses an older minor version. */
SLOW_TEST(build_cmake_find_package)
{
    if (!have("cmake") || !have("pkg-config")) {
        SKIP("no cmake or pkg-config (tools/deps.sh installs them)");
        return;
    }
    char dir[512], cwd[512], cmd[4096], log[700], soname[64];
    static char out[8192];
    CHECK(getcwd(cwd, sizeof cwd) != NULL, "the working directory");
    if (temp_dir("cmake-install", dir, sizeof dir)) return;
    soname_of(soname, sizeof soname);
    char *header = read_text_file("sky/sky.h", NULL);
    int api = 0;
    for (const char *p = header ? strstr(header, "\nSKY_API ") : NULL; p; p = strstr(p + 1, "\nSKY_API ")) api++;
    free(header);
    CHECK(api >= 30, "sky.h declares its functions with SKY_API (%d)", api);

    for (int shared = 0; shared < 2; shared++) {
        const char *kind = shared ? "shared" : "static";
        char prefix[600], lib[700];
        snprintf(prefix, sizeof prefix, "%s/prefix-%s", dir, kind);
        snprintf(lib, sizeof lib, "%s/lib", prefix);
        snprintf(log, sizeof log, "%s/libsky-%s.log", dir, kind);
        snprintf(cmd, sizeof cmd,
                 "cmake -S '%s' -B '%s/libsky-%s' -DSKY_WERROR=ON -DBUILD_SHARED_LIBS=%s -DCMAKE_INSTALL_PREFIX='%s' && "
                 "cmake --build '%s/libsky-%s' -j2 && cmake --install '%s/libsky-%s'",
                 cwd, dir, kind, shared ? "ON" : "OFF", prefix, dir, kind, dir, kind);
        int rc = run_logged(cmd, log, out, sizeof out);
        CHECK(rc == 0, "libsky (%s) configured, built and installed by CMake (exit %d): %s", kind, rc, out);
        if (rc) continue;

        CHECK(file_exists(prefix, "include/sky.h"), "%s: include/sky.h installed", kind);
        CHECK(file_exists(prefix, "lib/cmake/sky/skyConfig.cmake") &&
                  file_exists(prefix, "lib/cmake/sky/skyConfigVersion.cmake"),
              "%s: the CMake package installed", kind);
        CHECK(file_exists(prefix, "lib/pkgconfig/sky.pc"), "%s: sky.pc installed", kind);
        CHECK(file_exists(lib, shared ? soname : "libsky.a") && !file_exists(lib, shared ? "libsky.a" : "libsky.so"),
              "%s: lib/ holds %s and not the other kind", kind, shared ? soname : "libsky.a");
        if (shared) {
            snprintf(cmd, sizeof cmd, "readelf -d '%s/libsky.so' | grep SONAME", lib);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0 && strstr(out, soname), "the shared library's soname is %s: %s", soname, out);
            snprintf(cmd, sizeof cmd, "nm -D --defined-only '%s/libsky.so' | awk '{print $3}'", lib);
            rc = run_command(cmd, out, sizeof out);
            int exported = 0, foreign = 0;
            for (char *name = strtok(out, "\n"); rc == 0 && name; name = strtok(NULL, "\n")) {
                exported++;
                if (strncmp(name, "sky_", 4)) {
                    foreign++;
                    CHECK(0, "the shared library exports %s, which is not sky.h's", name);
                }
            }
            CHECK(exported == api && foreign == 0, "the shared library exports sky.h's %d functions alone (%d)", api,
                  exported);
        }

        /* find_package, asking for the header's MAJOR.MINOR */
        char build[700];
        snprintf(build, sizeof build, "%s/consumer-%s", dir, kind);
        snprintf(log, sizeof log, "%s/consumer-%s.log", dir, kind);
        snprintf(cmd, sizeof cmd,
                 "cmake -S '%s/tests/cmake/find_package' -B '%s' -DCMAKE_PREFIX_PATH='%s' -DSKY_VERSION_WANTED=%d.%d "
                 "'-DCMAKE_C_FLAGS=-Wall -Wextra -Werror' && cmake --build '%s'",
                 cwd, build, prefix, SKY_VERSION_MAJOR, SKY_VERSION_MINOR, build);
        rc = run_logged(cmd, log, out, sizeof out);
        CHECK(rc == 0, "%s: find_package's consumer builds (exit %d): %s", kind, rc, out);
        if (rc == 0) {
            snprintf(cmd, sizeof cmd, "'%s/consumer' 2>&1", build);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0, "%s: find_package's consumer ran (exit %d): %s", kind, rc, out);
            check_consumer_output(kind, out);
            snprintf(cmd, sizeof cmd, "env -u LD_LIBRARY_PATH ldd '%s/consumer' | grep libsky", build);
            rc = run_command(cmd, out, sizeof out);
            if (shared) CHECK(rc == 0 && strstr(out, lib), "the consumer loads libsky from %s: %s", lib, out);
            else CHECK(rc != 0, "the static consumer needs no libsky at run time: %s", out);
        }

        /* the installed sky.pc, shared through the rpath, static through --static */
        snprintf(cmd, sizeof cmd,
                 "PKG_CONFIG_PATH='%s/pkgconfig' && export PKG_CONFIG_PATH && "
                 "cc -std=c11 -Wall -Wextra -Werror '%s/tests/cmake/consumer.c' $(pkg-config %s--cflags --libs sky) %s%s "
                 "-o '%s/pc-%s' 2>&1 && '%s/pc-%s' 2>&1",
                 lib, cwd, shared ? "" : "--static ", shared ? "-Wl,-rpath," : "", shared ? lib : "", dir, kind, dir,
                 kind);
        rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0, "%s: the consumer builds and runs through the installed sky.pc (exit %d): %s", kind, rc, out);
        if (rc == 0) check_consumer_output(shared ? "sky.pc" : "sky.pc --static", out);

        /* sky.pc names the prefix given at install time, not only the
         * configured one */
        if (!shared) {
            char moved[700];
            snprintf(moved, sizeof moved, "%s/prefix-moved", dir);
            snprintf(cmd, sizeof cmd,
                     "cmake --install '%s/libsky-static' --prefix '%s' >/dev/null 2>&1 && "
                     "grep '^prefix=' '%s/lib/pkgconfig/sky.pc'",
                     dir, moved, moved);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0 && !strncmp(out, "prefix=", 7) && !strncmp(out + 7, moved, strlen(moved)) &&
                      out[7 + strlen(moved)] == '\n',
                  "cmake --install --prefix %s writes a sky.pc naming it: %s", moved, out);
        }

        /* Before 1.0 a minor version may break the ABI: the package
         * refuses a request for an older one (a lenient version file would
         * accept 0.MINOR-1). */
        if (!shared && SKY_VERSION_MAJOR == 0 && SKY_VERSION_MINOR > 0) {
            snprintf(cmd, sizeof cmd,
                     "cmake -S '%s/tests/cmake/find_package' -B '%s/consumer-older' -DCMAKE_PREFIX_PATH='%s' "
                     "-DSKY_VERSION_WANTED=0.%d 2>&1",
                     cwd, dir, prefix, SKY_VERSION_MINOR - 1);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc != 0 && strstr(out, "version"), "a request for 0.%d is refused (exit %d): %.400s",
                  SKY_VERSION_MINOR - 1, rc, out);
        }
    }
    remove_temp_dir(dir);
}

/* tests/cmake/add_subdirectory builds libsky inside its own build, with
 * clang where there is one (gcc builds it in the test above), warnings as
 * errors, and runs. The library it builds is the Makefile's: its members
 * are SKY_SRC's objects and the embedded blobs, no more and no fewer (both
 * read sky/sources.txt), and its generated sky_blobs.c is make's, byte for
 * byte. */
SLOW_TEST(build_cmake_add_subdirectory)
{
    if (!have("cmake")) {
        SKIP("no cmake (tools/deps.sh installs it)");
        return;
    }
    char dir[512], cwd[512], cmd[4096], log[700];
    static char out[8192], srcs[8192], members[8192];
    CHECK(getcwd(cwd, sizeof cwd) != NULL, "the working directory");
    if (temp_dir("cmake-subdir", dir, sizeof dir)) return;
    const char *cc = have("clang") ? "clang" : "cc";
    snprintf(log, sizeof log, "%s/build.log", dir);
    snprintf(cmd, sizeof cmd,
             "CC=%s cmake -S '%s/tests/cmake/add_subdirectory' -B '%s/b' -DSKY_SOURCE_DIR='%s' -DSKY_WERROR=ON "
             "'-DCMAKE_C_FLAGS=-Wall -Wextra -Werror' && cmake --build '%s/b' -j2",
             cc, cwd, dir, cwd, dir);
    int rc = run_logged(cmd, log, out, sizeof out);
    CHECK(rc == 0, "add_subdirectory's consumer builds with %s (exit %d): %s", cc, rc, out);
    if (rc == 0) {
        snprintf(cmd, sizeof cmd, "'%s/b/consumer' 2>&1", dir);
        rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0, "add_subdirectory's consumer ran (exit %d): %s", rc, out);
        check_consumer_output("add_subdirectory", out);

        /* the archive's members against make's list, each as a base name
         * (a .c.o from CMake, the source's name from make) */
        rc = run_command("make -s --no-print-directory --eval 'build-sources: ; @echo $(SKY_SRC) gen/sky_blobs.c' "
                         "build-sources 2>&1 | tr ' ' '\\n' | sed 's|.*/||; s|\\.c$||' | sort",
                         srcs, sizeof srcs);
        CHECK(rc == 0 && strstr(srcs, "sky_blobs\n"), "make names SKY_SRC (exit %d): %.200s", rc, srcs);
        snprintf(cmd, sizeof cmd, "ar t '%s/b/libsky/libsky.a' | sed 's|\\.c\\.o$||' | sort", dir);
        rc = run_command(cmd, members, sizeof members);
        int lines = 0;
        for (const char *p = members; *p; p++) lines += *p == '\n';
        CHECK(rc == 0 && !strcmp(srcs, members) && lines >= 40,
              "CMake's libsky.a holds make's SKY_SRC and the blobs (%d members)\n      make:  %.300s\n      cmake: %.300s",
              lines, srcs, members);
        if (access("build/gen/sky_blobs.c", R_OK) == 0) {
            snprintf(cmd, sizeof cmd, "cmp '%s/b/libsky/gen/sky_blobs.c' build/gen/sky_blobs.c 2>&1", dir);
            rc = run_command(cmd, out, sizeof out);
            CHECK(rc == 0, "CMake embeds the shaders and textures as make does: %s", out);
        }
    }
    remove_temp_dir(dir);
}

/* ---- README.md's "Use it in your build", as written ---------------------------------- */

/* The section's fenced blocks, in order: each sh block runs (sh -e) in a
 * copy of the tree when the paragraph before it says "from libsky's
 * directory", else in the project's directory, which holds the quick
 * start's program as game.c; the cmake block is the project's
 * CMakeLists.txt. HOME is the test's directory, so $HOME/sky is its own. */
typedef struct readme_block {
    const char *lang, *text, *before; /* before: the paragraph ahead of the fence */
    int lang_len, text_len, before_len;
} readme_block;

static int readme_blocks(const char *section, const char *end, readme_block *b, int max)
{
    int n = 0;
    const char *para = section;
    for (const char *p = section; p && p < end && n < max;) {
        const char *fence = strstr(p, "\n```");
        if (!fence || fence >= end) break;
        const char *lang = fence + 4, *nl = strchr(lang, '\n');
        const char *close = nl ? strstr(nl, "\n```") : NULL;
        if (!close || close >= end) break;
        /* the paragraph before: from the last blank line before the one
         * that opens the fence (at fence - 1) */
        for (const char *q = para; q && q + 1 < fence; q = strstr(q + 1, "\n\n")) para = q;
        b[n].lang = lang;
        b[n].lang_len = (int)(nl - lang);
        b[n].text = nl + 1;
        b[n].text_len = (int)(close - nl);
        b[n].before = para;
        b[n].before_len = (int)(fence - para);
        n++;
        p = close + 4;
        para = p;
    }
    return n;
}

/* The README's pkg-config and CMake instructions, run as they stand: the
 * install into $HOME/sky by make and by CMake from a copy of the tree (as
 * a clone would be, without build/), the quick start built against the
 * shared library, whose libsky the loader finds in $HOME/sky/lib through
 * the rpath, and against the static one, which needs none at run time,
 * and the CMake project built with find_package. Without a display each
 * program stops at glfwInit and returns 1: past the loader, so its
 * libraries resolved. */
SLOW_TEST(build_readme_commands)
{
    if (!have("cmake") || !have("pkg-config") || access("/usr/include/GLFW/glfw3.h", R_OK)) {
        SKIP("no cmake, pkg-config or GLFW (tools/deps.sh installs them)");
        return;
    }
    char *readme = read_text_file("README.md", NULL);
    CHECK(readme != NULL, "README.md readable");
    if (!readme) return;
    const char *section = strstr(readme, "\n## Use it in your build\n");
    const char *end = section ? strstr(section + 1, "\n## ") : NULL;
    const char *qs = strstr(readme, "## Quick start");
    const char *code = qs ? strstr(qs, "```c\n") : NULL;
    const char *code_end = code ? strstr(code + 5, "\n```") : NULL;
    CHECK(section && end && code && code_end, "the README has its quick start and \"Use it in your build\"");
    char dir[512], cmd[8192], path[800], home[600], tree[600], project[600];
    static char out[8192];
    if (!(section && end && code && code_end) || temp_dir("readme", dir, sizeof dir)) {
        free(readme);
        return;
    }
    snprintf(home, sizeof home, "%s/home", dir);
    snprintf(tree, sizeof tree, "%s/libsky", dir);
    snprintf(project, sizeof project, "%s/game", dir);
    /* the tree as a checkout has it: everything but build/ and .git */
    snprintf(cmd, sizeof cmd,
             "mkdir -p '%s' '%s' '%s' && tar --exclude=./build --exclude=./.git -cf - . | tar -xf - -C '%s' 2>&1", home,
             tree, project, tree);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "the tree copied (exit %d): %s", rc, out);
    snprintf(path, sizeof path, "%s/game.c", project);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "game.c written");
    if (f) {
        fwrite(code + 5, 1, (size_t)(code_end - code - 4), f);
        fclose(f);
    }

    readme_block b[16];
    int n = readme_blocks(section, end, b, 16), sh = 0, in_tree = 0, cmake = 0, failed = 0;
    for (int k = 0; k < n && rc == 0 && !failed; k++) {
        if (b[k].lang_len == 5 && !strncmp(b[k].lang, "cmake", 5)) {
            snprintf(path, sizeof path, "%s/CMakeLists.txt", project);
            f = fopen(path, "w");
            CHECK(f != NULL, "CMakeLists.txt written");
            if (f) {
                fwrite(b[k].text, 1, (size_t)b[k].text_len, f);
                fclose(f);
            }
            cmake++;
            continue;
        }
        if (b[k].lang_len != 2 || strncmp(b[k].lang, "sh", 2)) continue;
        char before[2048];
        snprintf(before, sizeof before, "%.*s", b[k].before_len, b[k].before);
        for (char *c = before; *c; c++)
            if (*c == '\n') *c = ' ';
        int tree_block = strstr(before, "from libsky's directory") != NULL;
        snprintf(path, sizeof path, "%s/block-%d.sh", dir, k);
        f = fopen(path, "w");
        CHECK(f != NULL, "the block written");
        if (!f) break;
        fwrite(b[k].text, 1, (size_t)b[k].text_len, f);
        fclose(f);
        char log[900];
        snprintf(log, sizeof log, "%s/block-%d.log", dir, k);
        /* make -j2 through MAKEFLAGS: the copy builds from nothing */
        snprintf(cmd, sizeof cmd,
                 "cd '%s' && env -u DISPLAY -u WAYLAND_DISPLAY -u PKG_CONFIG_PATH -u LD_LIBRARY_PATH HOME='%s' "
                 "MAKEFLAGS=-j2 sh -e '%s'",
                 tree_block ? tree : project, home, path);
        int brc = run_logged(cmd, log, out, sizeof out);
        CHECK(brc == 0, "README block %d (in %s) ran (exit %d):\n%.*s      %s", k, tree_block ? "the tree" : "the project",
              brc, b[k].text_len, b[k].text, out);
        failed = brc != 0;
        sh++;
        in_tree += tree_block;
    }
    CHECK(sh >= 4 && in_tree >= 2 && cmake == 1, "the section's blocks: %d sh (%d in the tree), %d cmake", sh, in_tree,
          cmake);

    char soname[64], lib[700];
    soname_of(soname, sizeof soname);
    snprintf(lib, sizeof lib, "%s/sky/lib", home);
    CHECK(file_exists(lib, soname) && file_exists(lib, "libsky.a") && file_exists(lib, "pkgconfig/sky.pc") &&
              file_exists(lib, "cmake/sky/skyConfig.cmake"),
          "$HOME/sky holds %s, libsky.a, sky.pc and the CMake package", soname);
    static const struct {
        const char *exe;
        int wants_shared;
    } programs[3] = {{"game", 1}, {"game-static", 0}, {"build/game", 0}};
    for (int k = 0; k < 3 && !failed; k++) {
        CHECK(file_exists(project, programs[k].exe), "the README's commands built %s", programs[k].exe);
        snprintf(cmd, sizeof cmd, "cd '%s' && env -u LD_LIBRARY_PATH ldd %s | grep libsky", project, programs[k].exe);
        rc = run_command(cmd, out, sizeof out);
        if (programs[k].wants_shared) {
            char want[1000];
            snprintf(want, sizeof want, "%s => %s/%s", soname, lib, soname);
            CHECK(rc == 0 && strstr(out, want), "%s finds libsky through its rpath (%s): %s", programs[k].exe, want, out);
        } else {
            CHECK(rc != 0, "%s needs no libsky at run time: %s", programs[k].exe, out);
        }
        snprintf(cmd, sizeof cmd, "cd '%s' && env -u DISPLAY -u WAYLAND_DISPLAY -u LD_LIBRARY_PATH ./%s 2>&1", project,
                 programs[k].exe);
        rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 1, "%s, with no display, stops at glfwInit and returns 1 (exit %d): %s", programs[k].exe, rc, out);
    }
    remove_temp_dir(dir);
    free(readme);
}
