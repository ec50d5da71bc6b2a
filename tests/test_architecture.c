/*
 * The library's shape, read from its sources (docs/ARCHITECTURE.md): no
 * raw GL call outside sky/gl/, no circle of three or more files calling
 * each other, and the hubs kept small (sky.c, each file of sky/gl/).
 * The sources are read as text from the repository's root, with comments
 * and string literals blanked first.
 */
#include "test.h"
#include "sky_internal.h"

#include <ctype.h>
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_FILES = 96, MAX_DEFS = 4096 };

typedef struct source {
    char path[512];
    char *code; /* comments and strings blanked, newlines kept */
    int lines;
} source;

typedef struct definition {
    char name[64];
    int file;
} definition;

/* Blanks comments and the insides of string and character literals, so
 * that what is left is code. */
static void blank_comments_and_strings(char *s)
{
    for (char *p = s; *p; p++) {
        if (p[0] == '/' && p[1] == '*') {
            char *end = strstr(p + 2, "*/");
            char *stop = end ? end + 2 : p + strlen(p);
            for (; p < stop; p++)
                if (*p != '\n') *p = ' ';
            p--;
        } else if (p[0] == '/' && p[1] == '/') {
            for (; *p && *p != '\n'; p++) *p = ' ';
            p--;
        } else if (*p == '"' || *p == '\'') {
            char quote = *p++;
            for (; *p && *p != quote && *p != '\n'; p++) {
                if (*p == '\\' && p[1]) *p++ = ' ';
                *p = ' ';
            }
            if (!*p) break;
        }
    }
}

/* The library's .c files (sky/, sky/atmosphere/, sky/gl/), without the
 * reference, which only the tools link. */
static int load_sources(source *out, int max)
{
    static const char *const dirs[3] = {"sky", "sky/atmosphere", "sky/gl"};
    int n = 0;
    for (int d = 0; d < 3; d++) {
        DIR *dir = opendir(dirs[d]);
        if (!dir) continue;
        struct dirent *e;
        while ((e = readdir(dir)) != NULL && n < max) {
            size_t len = strlen(e->d_name);
            if (len < 3 || strcmp(e->d_name + len - 2, ".c") || !strcmp(e->d_name, "reference.c")) continue;
            source *s = &out[n];
            int w = snprintf(s->path, sizeof s->path, "%s/%s", dirs[d], e->d_name);
            if (w < 0 || (size_t)w >= sizeof s->path) continue; /* (no such name in the tree) */
            s->code = read_text_file(s->path, NULL);
            if (!s->code) continue;
            blank_comments_and_strings(s->code);
            s->lines = 0;
            for (const char *p = s->code; *p; p++) s->lines += *p == '\n';
            n++;
        }
        closedir(dir);
    }
    return n;
}

static void free_sources(source *s, int n)
{
    for (int i = 0; i < n; i++) free(s[i].code);
}

static int ident_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

/* The sky_* names a file defines at file scope: a function (a line at
 * column 0 whose first sky_ name is followed by '(' and whose signature
 * ends in '{') or an object with an initialiser ("... sky_name = {" or
 * "... sky_name[..] = "). */
static int collect_definitions(const source *src, int n, definition *defs, int max)
{
    int count = 0;
    for (int f = 0; f < n; f++) {
        const char *line = src[f].code;
        while (*line) {
            const char *next = strchr(line, '\n');
            next = next ? next + 1 : line + strlen(line);
            if (isalpha((unsigned char)*line)) {
                const char *name = NULL;
                for (const char *p = line; p < next; p++)
                    if (!strncmp(p, "sky_", 4) && (p == line || !ident_char(p[-1]))) {
                        const char *q = p;
                        while (ident_char(*q)) q++;
                        while (*q == ' ') q++;
                        if (*q == '(' || *q == '=' || *q == '[') {
                            /* a function only if its signature ends in '{' */
                            int is_def = *q != '(';
                            if (*q == '(') {
                                const char *brace = strpbrk(q, "{;");
                                is_def = brace && *brace == '{';
                            }
                            if (is_def) name = p;
                            break;
                        }
                    }
                if (name && count < max) {
                    size_t len = 0;
                    while (ident_char(name[len]) && len + 1 < sizeof defs[count].name) len++;
                    memcpy(defs[count].name, name, len);
                    defs[count].name[len] = '\0';
                    defs[count].file = f;
                    count++;
                }
            }
            line = next;
        }
    }
    return count;
}

static int find_definition(const definition *defs, int count, const char *name, size_t len)
{
    for (int i = 0; i < count; i++)
        if (strlen(defs[i].name) == len && !strncmp(defs[i].name, name, len)) return defs[i].file;
    return -1;
}

/* Tarjan's strongly connected components over the file graph. */
typedef struct tarjan {
    const unsigned char (*edge)[MAX_FILES];
    int n, counter, top;
    int index[MAX_FILES], low[MAX_FILES], on_stack[MAX_FILES], stack[MAX_FILES], component[MAX_FILES];
    int components;
} tarjan;

static void strongconnect(tarjan *t, int v)
{
    t->index[v] = t->low[v] = t->counter++;
    t->stack[t->top++] = v;
    t->on_stack[v] = 1;
    for (int w = 0; w < t->n; w++) {
        if (!t->edge[v][w]) continue;
        if (t->index[w] < 0) {
            strongconnect(t, w);
            if (t->low[w] < t->low[v]) t->low[v] = t->low[w];
        } else if (t->on_stack[w] && t->index[w] < t->low[v]) {
            t->low[v] = t->index[w];
        }
    }
    if (t->low[v] == t->index[v]) {
        int w;
        do {
            w = t->stack[--t->top];
            t->on_stack[w] = 0;
            t->component[w] = t->components;
        } while (w != v);
        t->components++;
    }
}

TEST(architecture_no_call_circles)
{
    static source src[MAX_FILES];
    static definition defs[MAX_DEFS];
    static unsigned char edge[MAX_FILES][MAX_FILES];
    memset(edge, 0, sizeof edge);
    int n = load_sources(src, MAX_FILES);
    CHECK(n >= 30, "the library's sources are readable from the working directory (%d found)", n);
    int count = collect_definitions(src, n, defs, MAX_DEFS);
    int expected = find_definition(defs, count, "sky_create", 10) >= 0 &&
                   find_definition(defs, count, "sky_moon_layer", 14) >= 0;
    CHECK(expected, "the definitions found include sky_create and sky_moon_layer (%d found)", count);
    /* a file uses a name: an edge to the file that defines it */
    for (int f = 0; f < n; f++)
        for (const char *p = src[f].code; (p = strstr(p, "sky_")) != NULL;) {
            if (p > src[f].code && ident_char(p[-1])) {
                p += 4;
                continue;
            }
            size_t len = 0;
            while (ident_char(p[len])) len++;
            int g = find_definition(defs, count, p, len);
            if (g >= 0 && g != f) edge[f][g] = 1;
            p += len;
        }
    static tarjan t;
    memset(&t, 0, sizeof t);
    t.edge = (const unsigned char(*)[MAX_FILES])edge;
    t.n = n;
    for (int i = 0; i < n; i++) t.index[i] = -1;
    for (int i = 0; i < n; i++)
        if (t.index[i] < 0) strongconnect(&t, i);
    int edges = 0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) edges += edge[a][b];
    for (int c = 0; c < t.components; c++) {
        int size = 0;
        char members[1024] = "";
        for (int i = 0; i < n; i++)
            if (t.component[i] == c) {
                size++;
                if (strlen(members) + strlen(src[i].path) + 2 < sizeof members) {
                    strcat(members, " ");
                    strcat(members, src[i].path);
                }
            }
        if (size == 2) NOTE("two files call each other:%s", members);
        CHECK(size < 3, "a circle of %d files calling each other:%s", size, members);
    }
    NOTE("%d files, %d sky_* definitions, %d file-to-file uses", n, count, edges);
    free_sources(src, n);
}

TEST(architecture_no_raw_gl_outside_gl)
{
    static source src[MAX_FILES];
    int n = load_sources(src, MAX_FILES);
    CHECK(n >= 30, "the library's sources are readable (%d found)", n);
    int scanned = 0;
    for (int f = 0; f < n; f++) {
        if (!strncmp(src[f].path, "sky/gl/", 7)) continue;
        scanned++;
        /* a GL entry point is called through the loaded table: "glName(" */
        for (const char *p = src[f].code; (p = strstr(p, "gl")) != NULL; p += 2) {
            if (p > src[f].code && ident_char(p[-1])) continue;
            if (!isupper((unsigned char)p[2])) continue;
            const char *q = p + 2;
            while (ident_char(*q)) q++;
            while (*q == ' ') q++;
            if (*q != '(') continue;
            int line = 1;
            for (const char *r = src[f].code; r < p; r++) line += *r == '\n';
            CHECK(0, "%s:%d calls GL (%.*s) outside sky/gl/", src[f].path, line, (int)(q - p), p);
        }
    }
    CHECK(scanned >= 25, "only %d files outside sky/gl/ scanned", scanned);
    free_sources(src, n);
}

/* The hubs stay small: sky.c (the API and the composition) within 500
 * lines, each file of sky/gl/ (one role each) within 800. */
TEST(architecture_hubs_small)
{
    static source src[MAX_FILES];
    int n = load_sources(src, MAX_FILES);
    int saw_sky = 0, saw_gl = 0;
    for (int f = 0; f < n; f++) {
        if (!strcmp(src[f].path, "sky/sky.c")) {
            saw_sky = 1;
            CHECK(src[f].lines <= 500, "sky/sky.c has %d lines (at most 500)", src[f].lines);
        }
        if (!strncmp(src[f].path, "sky/gl/", 7)) {
            saw_gl++;
            CHECK(src[f].lines <= 800, "%s has %d lines (at most 800)", src[f].path, src[f].lines);
        }
    }
    CHECK(saw_sky && saw_gl >= 2, "sky/sky.c and sky/gl/*.c found (%d in gl/)", saw_gl);
    free_sources(src, n);
}

/* The layer table gives every row its own stats index, 0 .. count - 1 (a
 * layer after 0.5 that left .slot at 0 would share the star map's), and
 * every row its own name, which sky_layer_name and sky_layer_index
 * answer. */
TEST(architecture_layer_table_indices)
{
    int n = sky_layer_table_size, seen[64] = {0};
    CHECK(n == sky_layer_count() && n >= SKY_LAYER_COUNT && n <= 64, "%d rows, sky_layer_count %d", n,
          sky_layer_count());
    for (int row = 0; row < n && n <= 64; row++) {
        const sky_layer_class *L = sky_layer_table[row];
        int index = sky_layer_table_index(row);
        CHECK(index >= 0 && index < n, "%s: stats index %d outside 0..%d", L->name, index, n - 1);
        if (index < 0 || index >= n) continue;
        CHECK(!seen[index]++, "%s: stats index %d given twice", L->name, index);
        CHECK(L->name && !strcmp(sky_layer_name((sky_layer)index), L->name) && sky_layer_index(L->name) == index,
              "row %d: name %s, index %d, sky_layer_name %s, sky_layer_index %d", row, L->name ? L->name : "(none)",
              index, sky_layer_name((sky_layer)index), L->name ? sky_layer_index(L->name) : -2);
        CHECK(!L->glow_at == !L->glow_zenith, "%s: a night glow has both glow functions", L->name);
        CHECK(L->dome_role == SKY_DOME_NONE || L->dome_snippet, "%s: a dome role without a snippet", L->name);
    }
    CHECK(sky_layer_index("no such layer") == -1 && sky_layer_index(NULL) == -1, "unknown names give -1");
}
