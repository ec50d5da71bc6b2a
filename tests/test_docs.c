/*
 * The documents as a reader meets them. The repository stands alone: no
 * file a clone holds points to documents outside it. The README is a
 * front door of at most 300 lines whose quick start builds as it says.
 * Every relative link in the Markdown files reaches a file, and every
 * #anchor a heading (GitHub's slugs). And a figure is said once: a
 * measured figure in the README is quoted from the section of docs/ it
 * links to, and must stand there verbatim, so a rerun that changes the
 * doc and not the README (or the reverse) fails here.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

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
        size_t got;
        char *buf = read_text_file(path, &got);
        if (!buf) continue; /* listed but absent (deleted in the work tree) */
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

/* ---- Markdown: fences, headings, GitHub's anchors -------------------------------------- */

/* Whether the line at p opens or closes a fenced code block. */
static int is_fence(const char *p)
{
    while (*p == ' ') p++;
    return !strncmp(p, "```", 3) || !strncmp(p, "~~~", 3);
}

/* The heading level of the line at p (1..6), or 0. */
static int heading_level(const char *p)
{
    int n = 0;
    while (p[n] == '#') n++;
    return n >= 1 && n <= 6 && p[n] == ' ' ? n : 0;
}

/* One UTF-8 code point at *p, advancing *p past it (a stray byte is
 * taken as itself). */
static unsigned next_code_point(const unsigned char **p)
{
    const unsigned char *s = *p;
    unsigned c = s[0];
    int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
    for (int k = 1; k <= extra; k++) {
        if ((s[k] & 0xC0) != 0x80) {
            extra = 0;
            break;
        }
    }
    if (extra) {
        c &= 0x3Fu >> extra;
        for (int k = 1; k <= extra; k++) c = c << 6 | (s[k] & 0x3Fu);
    }
    *p = s + 1 + extra;
    return c;
}

static size_t put_utf8(unsigned c, char *out)
{
    if (c < 0x80) return out[0] = (char)c, 1;
    if (c < 0x800) return out[0] = (char)(0xC0 | c >> 6), out[1] = (char)(0x80 | (c & 63)), 2;
    if (c < 0x10000)
        return out[0] = (char)(0xE0 | c >> 12), out[1] = (char)(0x80 | (c >> 6 & 63)), out[2] = (char)(0x80 | (c & 63)), 3;
    out[0] = (char)(0xF0 | c >> 18), out[1] = (char)(0x80 | (c >> 12 & 63));
    out[2] = (char)(0x80 | (c >> 6 & 63)), out[3] = (char)(0x80 | (c & 63));
    return 4;
}

/* Whether GitHub keeps a code point in an anchor: it drops everything but
 * letters, marks, numbers, '-', '_' and spaces. Beyond ASCII, that is
 * judged by block, enough for these documents: Latin-1's letters and its
 * superscript digits, µ, ª and º stay, its signs (×, ÷, °, ±, ·, quotes)
 * go; general punctuation (dashes, quotes, ″), arrows and mathematical
 * signs go; other scripts stay. */
static int slug_keeps(unsigned c)
{
    if (c < 0x80) return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                         c == '_' || c == ' ';
    if (c < 0xC0) return c == 0xAA || c == 0xB2 || c == 0xB3 || c == 0xB5 || c == 0xB9 || c == 0xBA;
    if (c == 0xD7 || c == 0xF7) return 0;
    if (c >= 0x2000 && c <= 0x206F) return 0;
    if (c >= 0x2190 && c <= 0x2BFF) return 0;
    return 1;
}

/* GitHub's anchor for a heading's text (len bytes): lower case, spaces
 * to '-', the rest as slug_keeps says. */
static void slug_of(const char *text, size_t len, char *out, size_t out_len)
{
    const unsigned char *p = (const unsigned char *)text, *end = p + len;
    size_t n = 0;
    while (p < end && n + 5 < out_len) {
        unsigned c = next_code_point(&p);
        if (!slug_keeps(c)) continue;
        if (c >= 'A' && c <= 'Z') c += 32;
        if (c >= 0xC0 && c <= 0xDE) c += 0x20; /* Latin-1's capitals (× is gone already) */
        if (c == ' ') c = '-';
        n += put_utf8(c, out + n);
    }
    out[n] = '\0';
}

enum { MAX_HEADINGS = 256 };
typedef struct md_heading {
    char base[160], slug[168]; /* the anchor before and after GitHub's -1, -2 for a repeat */
    int level;
    const char *body, *end; /* the section: after its heading line, to the next heading of its level or above */
} md_heading;

/* The headings of a Markdown text outside code fences, with GitHub's
 * anchors (a repeated one gets -1, -2, ...). Returns how many. */
static int md_headings(const char *text, md_heading *h, int max)
{
    int n = 0, fenced = 0;
    for (const char *line = text; *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : line + strlen(line)) {
        if (is_fence(line)) fenced = !fenced;
        int level = fenced ? 0 : heading_level(line);
        if (!level || n == max) continue;
        const char *t = line + level + 1, *eol = strchr(t, '\n');
        if (!eol) eol = t + strlen(t);
        slug_of(t, (size_t)(eol - t), h[n].base, sizeof h[n].base);
        int seen = 0;
        for (int k = 0; k < n; k++) seen += !strcmp(h[k].base, h[n].base);
        if (seen) snprintf(h[n].slug, sizeof h[n].slug, "%.150s-%d", h[n].base, seen);
        else snprintf(h[n].slug, sizeof h[n].slug, "%s", h[n].base);
        h[n].level = level;
        h[n].body = *eol ? eol + 1 : eol;
        h[n].end = text + strlen(text);
        for (int k = n - 1; k >= 0; k--)
            if (h[k].end == text + strlen(text) && h[k].level >= level) h[k].end = line;
        n++;
    }
    return n;
}

/* The section of text whose anchor is slug, as [*from, *to); 0, or -1
 * when no heading has that anchor. */
static int md_section(const char *text, const char *slug, const char **from, const char **to)
{
    static md_heading h[MAX_HEADINGS];
    int n = md_headings(text, h, MAX_HEADINGS);
    for (int k = 0; k < n; k++)
        if (!strcmp(h[k].slug, slug)) {
            *from = h[k].body;
            *to = h[k].end;
            return 0;
        }
    return -1;
}

/* ---- links ----------------------------------------------------------------------------- */

/* The repository path a link from the file at `from` names (its '#'
 * part cut off first), with "." and ".." resolved; -1 if it climbs out of
 * the repository or is absolute. An empty target is the file itself. */
static int resolve_link(const char *from, const char *target, size_t target_len, char *out, size_t out_len)
{
    char buf[1024];
    if (!target_len) {
        snprintf(out, out_len, "%s", from);
        return 0;
    }
    if (target[0] == '/') return -1;
    const char *slash = strrchr(from, '/');
    int dir = slash ? (int)(slash - from + 1) : 0;
    snprintf(buf, sizeof buf, "%.*s%.*s", dir, from, (int)target_len, target);
    /* walk the segments */
    char *seg[64];
    int n = 0;
    for (char *save = NULL, *s = strtok_r(buf, "/", &save); s; s = strtok_r(NULL, "/", &save)) {
        if (!strcmp(s, ".")) continue;
        if (!strcmp(s, "..")) {
            if (!n) return -1;
            n--;
            continue;
        }
        if (n < 64) seg[n++] = s;
    }
    out[0] = '\0';
    for (int k = 0; k < n; k++) {
        size_t l = strlen(out);
        snprintf(out + l, out_len - l, "%s%s", k ? "/" : "", seg[k]);
    }
    return 0;
}

/* Calls fn for each link target in a Markdown text outside code fences
 * and inline code: "](target)" (links and images) and src="target"
 * (the README's <img> tags). The target runs to ')' or '"', a space
 * (a title) ending it too. */
typedef void (*link_fn)(const char *target, size_t len, const char *at, void *ctx);
static void md_links(const char *text, link_fn fn, void *ctx)
{
    int fenced = 0, code = 0;
    for (const char *p = text; *p; p++) {
        if ((p == text || p[-1] == '\n') && is_fence(p)) {
            fenced = !fenced;
            p = strchr(p, '\n');
            if (!p) return;
            continue;
        }
        if (fenced) continue;
        if (*p == '`') code = !code;
        if (*p == '\n' && p[1] == '\n') code = 0; /* an unclosed span ends with its paragraph */
        if (code) continue;
        const char *t = NULL;
        char close = ')';
        if (p[0] == ']' && p[1] == '(') t = p + 2;
        else if (!strncmp(p, "src=\"", 5)) t = p + 5, close = '"';
        if (!t) continue;
        size_t len = 0;
        while (t[len] && t[len] != close && t[len] != ' ' && t[len] != '\n') len++;
        fn(t, len, p, ctx);
    }
}

typedef struct link_check {
    const char *file, *text;
    int links, anchors, external;
} link_check;

static int line_of(const char *text, const char *at)
{
    int n = 1;
    for (const char *p = text; p < at; p++) n += *p == '\n';
    return n;
}

static void check_link(const char *target, size_t len, const char *at, void *ctx)
{
    link_check *c = ctx;
    if (!strncmp(target, "http://", 7) || !strncmp(target, "https://", 8) || !strncmp(target, "mailto:", 7)) {
        c->external++;
        return;
    }
    c->links++;
    const char *hash = memchr(target, '#', len);
    size_t path_len = hash ? (size_t)(hash - target) : len;
    char path[1024];
    if (resolve_link(c->file, target, path_len, path, sizeof path)) {
        CHECK(0, "%s:%d: the link %.*s leaves the repository", c->file, line_of(c->text, at), (int)len, target);
        return;
    }
    struct stat st;
    if (stat(path, &st)) {
        CHECK(0, "%s:%d: the link %.*s names %s, which does not exist", c->file, line_of(c->text, at), (int)len, target,
              path);
        return;
    }
    if (!hash) return;
    c->anchors++;
    char slug[256];
    snprintf(slug, sizeof slug, "%.*s", (int)(len - path_len - 1), hash + 1);
    size_t plen = strlen(path);
    if (plen < 3 || strcmp(path + plen - 3, ".md")) {
        CHECK(0, "%s:%d: the link %.*s has an anchor into %s, which is not Markdown", c->file, line_of(c->text, at),
              (int)len, target, path);
        return;
    }
    char *doc = read_text_file(path, NULL);
    const char *from, *to;
    CHECK(doc && md_section(doc, slug, &from, &to) == 0, "%s:%d: the link %.*s: %s has no heading whose anchor is #%s",
          c->file, line_of(c->text, at), (int)len, target, path, slug);
    free(doc);
}

/* The Markdown files a reader follows: every tracked *.md (or, outside
 * git, those found), one per line into list. */
static int list_markdown(char *list, size_t len)
{
    int rc = run_command("git ls-files '*.md' 2>/dev/null", list, len);
    if (rc == 0 && list[0]) return 0;
    rc = run_command("find . -path ./build -prune -o -path ./.git -prune -o -name '*.md' -print 2>/dev/null | "
                     "sed 's|^\\./||'",
                     list, len);
    return rc == 0 && list[0] ? 0 : -1;
}

/* Every relative link in the Markdown files reaches a file inside the
 * repository, and every #anchor a heading of the file it names. */
TEST(docs_links_resolve)
{
    static char list[1 << 16];
    CHECK(list_markdown(list, sizeof list) == 0, "cannot list the Markdown files");
    int files = 0, links = 0, anchors = 0, readme_links = 0;
    for (char *line = strtok(list, "\n"); line; line = strtok(NULL, "\n")) {
        char *text = read_text_file(line, NULL);
        if (!text) continue;
        link_check c = {line, text, 0, 0, 0};
        md_links(text, check_link, &c);
        files++;
        links += c.links;
        anchors += c.anchors;
        if (!strcmp(line, "README.md")) readme_links = c.links;
        free(text);
    }
    NOTE("%d Markdown files, %d relative links, %d of them with an anchor", files, links, anchors);
    CHECK(files >= 5 && readme_links >= 20 && anchors >= 20,
          "the check saw the documents (%d files, %d links in the README, %d anchors)", files, readme_links, anchors);

    /* the checker itself, on cases whose answer is known */
    char slug[160];
    static const struct {
        const char *heading, *slug;
    } cases[] = {{"Measured (llvmpipe, 2 cores, 1280×720)", "measured-llvmpipe-2-cores-1280720"},
                 {"OpenGL ES 2.0 and WebGL 1", "opengl-es-20-and-webgl-1"},
                 {"In a browser: `make web`", "in-a-browser-make-web"},
                 {"The sun's disc", "the-suns-disc"},
                 {"Müller's night — the stars", "müllers-night--the-stars"},
                 {"sky_update and sky_draw", "sky_update-and-sky_draw"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        slug_of(cases[k].heading, strlen(cases[k].heading), slug, sizeof slug);
        CHECK(!strcmp(slug, cases[k].slug), "the anchor of \"%s\" is %s, not %s", cases[k].heading, cases[k].slug, slug);
    }
    static md_heading h[8];
    int n = md_headings("# A\n\n## Same\ntext\n```\n## not a heading\n```\n## Same\n### Deeper\n## Other\n", h, 8);
    CHECK(n == 5 && !strcmp(h[1].slug, "same") && !strcmp(h[2].slug, "same-1") && !strcmp(h[4].slug, "other"),
          "headings in fences are not headings, and a repeated anchor gets -1 (%d headings)", n);
    CHECK(n == 5 && h[2].end == strstr(h[2].body, "## Other"), "a section runs over its subsections to the next of its level");
    char path[256];
    CHECK(resolve_link("docs/guide.md", "../README.md", 12, path, sizeof path) == 0 && !strcmp(path, "README.md") &&
              resolve_link("docs/guide.md", "img/a.png", 9, path, sizeof path) == 0 && !strcmp(path, "docs/img/a.png") &&
              resolve_link("README.md", "../" "elsewhere/x.md", 17, path, sizeof path) == -1,
          "links resolve from the file's own directory, and none climbs out");
}

/* ---- figures: the README quotes, the docs hold ------------------------------------------ */

/* The units of the library's measured quantities. A number followed by
 * one of these is a figure; "1280×720" (× before a digit) is a size and
 * "45° N" a place, not figures. Seconds are left out on purpose: the
 * README's "about 35 s" for make check is a note on the build, and a
 * figure's "s" would catch durations of every kind. */
static const char *const units[] = {"ms", "µs", "us", "×", "%", "dB", "°", "″", "′", "klx", "lx", "kcd/m²",
                                    "mag/arcsec²", "MiB"};

static int is_digit(char c) { return c >= '0' && c <= '9'; }
static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/* Whether a figure (a number and a unit) starts at p, where a number may
 * start; its number's length in *num_len. */
static int figure_at(const char *text, const char *p, size_t *num_len)
{
    if (!is_digit(*p)) return 0;
    if (p > text && (is_digit(p[-1]) || p[-1] == '.' || is_alpha(p[-1]) || p[-1] == '_')) return 0;
    const char *q = p;
    while (is_digit(*q)) q++;
    if (*q == '.' && is_digit(q[1]))
        for (q++; is_digit(*q);) q++;
    *num_len = (size_t)(q - p);
    const char *u = q;
    if (*u == ' ') u++;
    else if (!strncmp(u, "\xc2\xa0", 2) || !strncmp(u, "\xe2\x80\xaf", 3)) /* no-break and narrow no-break spaces */
        u += u[0] == '\xc2' ? 2 : 3;
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++) {
        size_t l = strlen(units[k]);
        if (strncmp(u, units[k], l)) continue;
        const char *after = u + l;
        if (is_alpha(units[k][0]) && (is_alpha(*after) || *after == '/')) continue; /* "us" in "use" */
        if (!strcmp(units[k], "×") && (is_digit(*after) || (*after == ' ' && is_digit(after[1])))) return 0;
        if (!strcmp(units[k], "°")) {
            const char *d = after + (*after == ' ');
            if ((*d == 'N' || *d == 'S' || *d == 'E' || *d == 'W') && !is_alpha(d[1])) return 0;
        }
        return 1;
    }
    return 0;
}

/* Whether the number (len bytes at num) stands in [from, to) as a number
 * of its own: not a part of 11.42 or 1.425. */
static int number_in(const char *num, size_t len, const char *from, const char *to)
{
    for (const char *p = from; p + len <= to; p++) {
        if (strncmp(p, num, len)) continue;
        if (p > from && (is_digit(p[-1]) || (p[-1] == '.' && p - 1 > from && is_digit(p[-2])))) continue;
        const char *e = p + len;
        if (e < to && (is_digit(*e) || (*e == '.' && e + 1 < to && is_digit(e[1])))) continue;
        return 1;
    }
    return 0;
}

/* The README's blocks: paragraphs (to a blank line), and each table row,
list item and heading on its own; fenced and indented code left out.
Calls fn for each. */
typedef void (*block_fn)(const char *from, const char *to, void *ctx);
static void md_blocks(const char *text, block_fn fn, void *ctx)
{
    const char *start = NULL;
    int fenced = 0;
    for (const char *line = text; *line;) {
        const char *eol = strchr(line, '\n');
        const char *next = eol ? eol + 1 : line + strlen(line);
        if (is_fence(line) || fenced || *line == '\n' || (!start && !strncmp(line, "    ", 4))) {
            if (start) fn(start, line, ctx);
            start = NULL;
            fenced ^= is_fence(line);
        } else if (*line == '|' || heading_level(line)) {
            if (start) fn(start, line, ctx);
            start = NULL;
            fn(line, next, ctx);
        } else if (!strncmp(line, "- ", 2) || !strncmp(line, "* ", 2)) {
            if (start) fn(start, line, ctx);
            start = line;
        } else if (!start)
            start = line;
        line = next;
    }
    if (start) fn(start, start + strlen(start), ctx);
}

typedef struct figure_check {
    const char *text; /* the README's */
    int figures, blocks, outside_docs;
} figure_check;

/* A block's links into docs/ (path and anchor), collected by md_links. */
typedef struct block_links {
    int n;
    char path[8][256], slug[8][160];
} block_links;

static void collect_doc_link(const char *target, size_t len, const char *at, void *ctx)
{
    (void)at;
    block_links *b = ctx;
    if (b->n == 8 || strncmp(target, "docs/", 5)) return;
    const char *hash = memchr(target, '#', len);
    size_t path_len = hash ? (size_t)(hash - target) : len;
    if (path_len < 3 || strncmp(target + path_len - 3, ".md", 3)) return;
    snprintf(b->path[b->n], sizeof b->path[b->n], "%.*s", (int)path_len, target);
    snprintf(b->slug[b->n], sizeof b->slug[b->n], "%.*s", hash ? (int)(len - path_len - 1) : 0, hash ? hash + 1 : "");
    b->n++;
}

static void check_block(const char *from, const char *to, void *ctx)
{
    figure_check *c = ctx;
    char block[4096];
    snprintf(block, sizeof block, "%.*s", (int)(to - from), from);
    block_links links = {0};
    md_links(block, collect_doc_link, &links);
    int counted = 0;
    for (const char *p = block; *p; p++) {
        size_t len;
        if (!figure_at(block, p, &len)) continue;
        c->figures++;
        counted = 1;
        int found = 0;
        for (int k = 0; k < links.n && !found; k++) {
            char *doc = read_text_file(links.path[k], NULL);
            const char *sf = doc, *st = doc ? doc + strlen(doc) : NULL;
            if (doc && (!links.slug[k][0] || md_section(doc, links.slug[k], &sf, &st) == 0))
                found = number_in(p, len, sf, st);
            free(doc);
        }
        if (!links.n) c->outside_docs++;
        size_t shown = strcspn(p, "\n,;)");
        CHECK(found, "README.md:%d: the figure \"%.*s\" is %s", line_of(c->text, from), (int)(shown < 24 ? shown : 24),
              p, links.n ? "not in the doc section that its line links to" : "in a line that cites no doc in docs/");
        p += len - 1;
    }
    c->blocks += counted;
}

/* Every measured figure in the README (a number with a unit of the
 * library's quantities, outside code) sits in a line, table row or
 * paragraph that links to a doc in docs/, and its number stands verbatim
 * in the section linked. So the README's feature and cost lines quote
 * docs/benchmarks.md and docs/validation.md, and a regenerated doc whose
 * figures moved fails here until the README says the same. */
TEST(docs_readme_figures_quoted_from_docs)
{
    char *readme = read_text_file("README.md", NULL);
    CHECK(readme != NULL, "README.md readable from the working directory");
    if (!readme) return;
    figure_check c = {readme, 0, 0, 0};
    md_blocks(readme, check_block, &c);
    NOTE("%d figures in %d blocks of the README checked against the docs they cite", c.figures, c.blocks);
    CHECK(c.figures >= 6, "the README quotes some figures (%d): the check is not empty", c.figures);
    free(readme);

    /* the checker itself */
    size_t len;
    static const char *const is[] = {"1.42×", "2.2 %", "6.6 µs", "0.00016°", "49 dB", "20.8 us"};
    static const char *const not_figures[] = {"1280×720", "45° N", "V 6.5", "GLSL 1.10", "35 s", "2005", "x1.5",
                                              "8 users"};
    for (size_t k = 0; k < sizeof is / sizeof is[0]; k++)
        CHECK(figure_at(is[k], is[k], &len), "%s is a figure", is[k]);
    for (size_t k = 0; k < sizeof not_figures / sizeof not_figures[0]; k++) {
        int any = 0;
        for (const char *p = not_figures[k]; *p; p++) any |= figure_at(not_figures[k], p, &len);
        CHECK(!any, "%s is not a figure", not_figures[k]);
    }
    static const char doc[] = "| minimal | 11.42 | 1.425 | 2.26 |";
    CHECK(!number_in("1.42", 4, doc, doc + strlen(doc)) && number_in("2.26", 4, doc, doc + strlen(doc)),
          "a number is found on its own, not inside another");
}

/* The docs say one thing once, too: the astronomy's cost where the
 * astronomy is validated is the figure of the benchmark's Astronomy
 * section (they once said 13 and 8.1 us); the LDR output's tone map is
 * not called exponential (the maps are hue, filmic and neutral), and the
 * guide's Colour table has a row for each. */
TEST(docs_figures_agree)
{
    char *validation = read_text_file("docs/validation.md", NULL), *bench = read_text_file("docs/benchmarks.md", NULL);
    char *guide = read_text_file("docs/guide.md", NULL), *readme = read_text_file("README.md", NULL);
    CHECK(validation && bench && guide && readme, "README.md and docs/ readable from the working directory");
    if (validation && bench && guide && readme) {
        const char *prose = strstr(validation, "astronomy update costs ");
        const char *measured = strstr(bench, "Astronomy: ");
        CHECK(prose && measured, "both figures are there (validation.md %s, benchmarks.md %s)", prose ? "yes" : "no",
              measured ? "yes" : "no");
        if (prose && measured) {
            const char *q = prose + strlen("astronomy update costs ");
            if (!strncmp(q, "about ", 6)) q += 6;
            double a = strtod(q, NULL);
            double b = strtod(measured + strlen("Astronomy: "), NULL);
            CHECK(a > 0.0 && a == b, "the astronomy's cost: %g us in validation.md, %g us in benchmarks.md", a, b);
        }
        const char *const texts[4] = {readme, guide, validation, bench};
        for (int k = 0; k < 4; k++) CHECK(!strstr(texts[k], "exponential tone map"), "a doc calls a tone map exponential");
        static const char *const maps[3] = {"| `hue` (default) |", "| `filmic` |", "| `neutral` |"};
        for (int k = 0; k < 3; k++)
            CHECK(strstr(guide, maps[k]) != NULL, "the guide's Colour table has the row %s", maps[k]);
    }
    free(validation);
    free(bench);
    free(guide);
    free(readme);
}

/* ---- the README as a front door ------------------------------------------------------------ */

/* At most 300 lines (later issues add one row and one picture each to
 * its feature table and their sections to docs/), a table of contents
 * that lists every ## section, the two commands, a quick start with its
 * build line, the feature table. */
TEST(docs_readme_is_a_front_door)
{
    char *readme = read_text_file("README.md", NULL);
    CHECK(readme != NULL, "README.md readable from the working directory");
    if (!readme) return;
    int lines = 0;
    for (const char *p = readme; *p; p++) lines += *p == '\n';
    CHECK(lines <= 300, "README.md has %d lines, over 300: what is not the front door goes to docs/", lines);
    static md_heading h[MAX_HEADINGS];
    int n = md_headings(readme, h, MAX_HEADINGS), sections = 0;
    for (int k = 0; k < n; k++) {
        if (h[k].level != 2) continue;
        sections++;
        char link[200];
        snprintf(link, sizeof link, "](#%s)", h[k].slug);
        CHECK(strstr(readme, link) != NULL, "the table of contents lists the section #%s", h[k].slug);
    }
    CHECK(sections >= 4, "the README has its sections (%d)", sections);
    CHECK(strstr(readme, "make run") && strstr(readme, "make test") && strstr(readme, "make check"), "the commands");
    CHECK(strstr(readme, "pkg-config --cflags --libs sky") && strstr(readme, "build/lib/libsky.a"),
          "the quick start's build lines, installed and in the tree");
    CHECK(strstr(readme, "| phenomenon | after | picture | in the docs |") != NULL, "the feature table");
    free(readme);
}

/* The quick start and its in-tree build line are true: the README's C
 * program, compiled and linked by the README's own command (run from the
 * repository's root, the output sent to a temporary file), warns of
 * nothing under -Wall -Wextra. */
TEST(docs_quick_start_builds)
{
    char *readme = read_text_file("README.md", NULL);
    CHECK(readme != NULL, "README.md readable");
    if (!readme) return;
    struct stat st;
    if (stat("/usr/include/GLFW/glfw3.h", &st) || stat("build/lib/libsky.a", &st)) {
        SKIP("no GLFW header or no build/lib/libsky.a (make builds it)");
        free(readme);
        return;
    }
    const char *qs = strstr(readme, "## Quick start");
    const char *code = qs ? strstr(qs, "```c\n") : NULL;
    const char *code_end = code ? strstr(code + 5, "\n```") : NULL;
    const char *line = code_end ? strstr(code_end, "\n    cc ") : NULL;
    CHECK(code && code_end && line, "the quick start has its C block and an indented cc line after it");
    if (!(code && code_end && line)) {
        free(readme);
        return;
    }
    char src[] = "/tmp/sky-quick-start-XXXXXX";
    int fd = mkstemp(src);
    CHECK(fd >= 0, "a temporary file");
    if (fd < 0) {
        free(readme);
        return;
    }
    FILE *f = fdopen(fd, "w");
    fwrite(code + 5, 1, (size_t)(code_end - code - 4), f);
    fclose(f);
    /* the README's command, its game.c the temporary copy, -Wall -Wextra -Werror and -x c added */
    char cmd_line[512], cmd[2048], out[4096];
    const char *eol = strchr(line + 1, '\n');
    snprintf(cmd_line, sizeof cmd_line, "%.*s", (int)(eol - line - 5), line + 5);
    char *game = strstr(cmd_line, " game.c ");
    CHECK(game != NULL, "the build line names game.c: %s", cmd_line);
    if (game) {
        *game = '\0';
        snprintf(cmd, sizeof cmd, "%s -Wall -Wextra -Werror -x c %s -x none %s -o %s.bin 2>&1", cmd_line, src, game + 8,
                 src);
        int rc = run_command(cmd, out, sizeof out);
        CHECK(rc == 0, "the quick start builds with the README's line (exit %d): %s\n      %s", rc, cmd, out);
        char bin[64];
        snprintf(bin, sizeof bin, "%s.bin", src);
        remove(bin);
    }
    remove(src);
    free(readme);
}

/* ---- the commands the docs give ------------------------------------------------------------ */


/* A figure's command must run what the doc says: every "sky-tests NAME"
 * in README.md and the Markdown of docs/ names at least one test of the runner (by
 * substring, as the runner selects), and every "sky-bench --OPTION" an
 * option sky-bench's usage lists. */
TEST(docs_commands_are_real)
{
    static char list[1 << 16], usage[8192], names[1 << 16];
    char path[512], cmd[1024];
    /* the runner's tests, found as tests/list.sh finds them: TEST(name) and
     * SLOW_TEST(name) at a line's start in tests/ *.c */
    CHECK(run_command("sed -n 's/^\\(SLOW_\\)\\{0,1\\}TEST(\\([a-z0-9_]*\\)).*/\\2/p' tests/*.c", names,
                      sizeof names) == 0 &&
              strstr(names, "docs_commands_are_real\n"),
          "the runner's test names read from tests/*.c: %.100s", names);
    snprintf(cmd, sizeof cmd, "%s --help 2>&1", bin_path("sky-bench", path, sizeof path));
    int have_usage = run_command(cmd, usage, sizeof usage) == 0 && strstr(usage, "usage:");
    CHECK(have_usage, "sky-bench --help prints its usage: %.200s", usage);
    CHECK(list_markdown(list, sizeof list) == 0, "cannot list the Markdown files");
    int tests = 0, options = 0;
    for (char *line = strtok(list, "\n"); line; line = strtok(NULL, "\n")) {
        if (strcmp(line, "README.md") && strncmp(line, "docs/", 5)) continue;
        char *text = read_text_file(line, NULL);
        if (!text) continue;
        for (const char *p = strstr(text, "sky-tests"); p; p = strstr(p + 1, "sky-tests")) {
            const char *q = p + strlen("sky-tests");
            while (*q == ' ' || *q == '\n') q++;
            size_t n = strspn(q, "abcdefghijklmnopqrstuvwxyz0123456789_");
            if (!n || q == p + strlen("sky-tests")) continue; /* "sky-tests NAME", "sky-tests.c" */
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)n, q);
            /* the runner selects by substring: a name that occurs in a test's name */
            CHECK(strstr(names, name) != NULL, "%s:%d: `sky-tests %s` runs no test", line, line_of(text, p), name);
            tests++;
        }
        for (const char *p = strstr(text, "sky-bench --"); p && have_usage; p = strstr(p + 1, "sky-bench --")) {
            const char *q = p + strlen("sky-bench ");
            char opt[64];
            snprintf(opt, sizeof opt, "%.*s", (int)strspn(q, "-abcdefghijklmnopqrstuvwxyz"), q);
            CHECK(strstr(usage, opt) != NULL, "%s:%d: sky-bench has no option %s", line, line_of(text, p), opt);
            options++;
        }
        free(text);
    }
    NOTE("%d sky-tests commands and %d sky-bench options in the docs, each real", tests, options);
    CHECK(tests >= 40 && options >= 8, "the docs give their commands (%d tests, %d options)", tests, options);
}
