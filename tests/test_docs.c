/*
 * The repository stands alone: no file a clone holds points to documents
 * outside it (a sibling directory beside the clone, or the design and
 * anchor notes that lived there), which a reader of the clone cannot open.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

/* Split so that this file does not match itself. */
static const char *const outside[] = {"../" "shared/", "DESIGN" ".md", "ANCHORS" ".md"};

/* The files to scan: git's tracked files, or, outside a git checkout (an
 * unpacked archive), every file under the working directory; build/ and
 * .git/ left out either way. One path per line into list. */
static int list_files(char *list, size_t len)
{
    int rc = run_command("git ls-files 2>/dev/null", list, len);
    if (rc == 0 && list[0]) return 0;
    rc = run_command("find . -path ./build -prune -o -path ./.git -prune -o -type f -print 2>/dev/null", list, len);
    return rc == 0 && list[0] ? 0 : -1;
}

TEST(docs_no_paths_outside_the_repository)
{
    static char list[1 << 20];
    int have_list = list_files(list, sizeof list) == 0;
    CHECK(have_list, "cannot list the repository's files");
    if (!have_list) return;
    CHECK(strlen(list) + 1 < sizeof list, "the file list fits its buffer (%zu bytes)", strlen(list));
    int files = 0, text = 0, saw_cli = 0, saw_readme = 0;
    for (char *line = strtok(list, "\n"); line; line = strtok(NULL, "\n")) {
        const char *path = !strncmp(line, "./", 2) ? line + 2 : line;
        if (!strncmp(path, "build/", 6) || !strncmp(path, ".git/", 5)) continue;
        files++;
        FILE *f = fopen(path, "rb");
        if (!f) continue; /* listed but absent (deleted in the work tree) */
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        fseek(f, 0, SEEK_SET);
        char *buf = size >= 0 ? malloc((size_t)size + 1) : NULL;
        size_t got = buf ? fread(buf, 1, (size_t)size, f) : 0;
        fclose(f);
        if (!buf) continue;
        buf[got] = '\0';
        /* text only: a PNG or a star catalogue may hold any bytes */
        if (memchr(buf, '\0', got)) {
            free(buf);
            continue;
        }
        text++;
        saw_cli |= !strcmp(path, "demo/cli.c");
        saw_readme |= !strcmp(path, "README.md");
        for (size_t k = 0; k < sizeof outside / sizeof outside[0]; k++) {
            const char *hit = strstr(buf, outside[k]);
            if (!hit) continue;
            int line_no = 1;
            for (const char *p = buf; p < hit; p++) line_no += *p == '\n';
            CHECK(0, "%s:%d mentions %s, which a clone does not have", path, line_no, outside[k]);
        }
        free(buf);
    }
    NOTE("%d files listed, %d text files scanned", files, text);
    CHECK(saw_readme && saw_cli, "the scan covered README.md and demo/cli.c");
}

/* README.md, whole, or NULL. */
static char *read_readme(void)
{
    FILE *f = fopen("README.md", "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = size > 0 ? malloc((size_t)size + 1) : NULL;
    size_t got = buf ? fread(buf, 1, (size_t)size, f) : 0;
    fclose(f);
    if (buf) buf[got] = '\0';
    return buf;
}

/* The README says one thing once: the astronomy's cost where the
 * astronomy is described is the figure of the Measured section (sky-bench's
 * "astronomy:" line; they said 13 and 8.1 us), and the LDR output's tone
 * map is not called exponential (the maps are hue, filmic and neutral). */
TEST(docs_readme_figures_agree)
{
    char *readme = read_readme();
    CHECK(readme != NULL, "README.md readable from the working directory");
    if (!readme) return;
    const char *prose = strstr(readme, "astronomy update costs ");
    const char *measured = strstr(readme, "Astronomy: ");
    CHECK(prose && measured, "both figures are there (prose %s, Measured %s)", prose ? "yes" : "no",
          measured ? "yes" : "no");
    if (prose && measured) {
        const char *q = prose + strlen("astronomy update costs ");
        if (!strncmp(q, "about ", 6)) q += 6;
        double a = strtod(q, NULL);
        double b = strtod(measured + strlen("Astronomy: "), NULL);
        CHECK(a > 0.0 && a == b, "the astronomy's cost: %g us in the prose, %g us in Measured", a, b);
    }
    CHECK(!strstr(readme, "exponential tone map"), "README calls a tone map exponential");
    static const char *const maps[3] = {"| `hue` (default) |", "| `filmic` |", "| `neutral` |"};
    for (int k = 0; k < 3; k++) CHECK(strstr(readme, maps[k]) != NULL, "the Colour table has the row %s", maps[k]);
    free(readme);
}
