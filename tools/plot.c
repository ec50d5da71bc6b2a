/*
 * See plot.h. Everything is drawn into an RGB buffer by hand: lines,
 * discs, rings and 3x5 glyphs scaled 2x.
 */
#include "plot.h"

#include "osmesa_ctx.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 720
#define H 450
#define LEFT 70
#define RIGHT 190
#define TOP 40
#define BOTTOM 60

typedef struct canvas {
    unsigned char px[W * H * 3];
} canvas;

static void put(canvas *c, int x, int y, const unsigned char rgb[3])
{
    if (x < 0 || y < 0 || x >= W || y >= H) return;
    memcpy(c->px + (y * W + x) * 3, rgb, 3);
}

static void line(canvas *c, double x0, double y0, double x1, double y1, const unsigned char rgb[3])
{
    int n = (int)(fmax(fabs(x1 - x0), fabs(y1 - y0))) + 1;
    for (int i = 0; i <= n; i++) {
        double t = (double)i / n;
        put(c, (int)lround(x0 + (x1 - x0) * t), (int)lround(y0 + (y1 - y0) * t), rgb);
    }
}

static void disc(canvas *c, double cx, double cy, double r, int hollow, const unsigned char rgb[3])
{
    for (int y = (int)(cy - r - 1); y <= (int)(cy + r + 1); y++)
        for (int x = (int)(cx - r - 1); x <= (int)(cx + r + 1); x++) {
            double d = hypot(x - cx, y - cy);
            if (d <= r && (!hollow || d >= r - 2.0)) put(c, x, y, rgb);
        }
}

/* 3x5 glyphs: five rows of three bits, the high bit on the left. */
static int glyph(char ch, unsigned short *bits)
{
    static const char *chars = "0123456789.%x()/-,:=>ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    static const unsigned short rows[][5] = {
        {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
        {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7},
        {0, 0, 0, 0, 2}, {5, 1, 2, 4, 5}, {0, 5, 2, 5, 0}, {2, 4, 4, 4, 2}, {2, 1, 1, 1, 2},
        {1, 1, 2, 4, 4}, {0, 0, 7, 0, 0}, {0, 0, 0, 2, 4}, {0, 2, 0, 2, 0}, {0, 7, 0, 7, 0},
        {4, 2, 1, 2, 4},
        {2, 5, 7, 5, 5}, {6, 5, 6, 5, 6}, {3, 4, 4, 4, 3}, {6, 5, 5, 5, 6}, {7, 4, 6, 4, 7},
        {7, 4, 6, 4, 4}, {3, 4, 5, 5, 3}, {5, 5, 7, 5, 5}, {7, 2, 2, 2, 7}, {1, 1, 1, 5, 2},
        {5, 5, 6, 5, 5}, {4, 4, 4, 4, 7}, {5, 7, 7, 5, 5}, {6, 5, 5, 5, 5}, {2, 5, 5, 5, 2},
        {6, 5, 6, 4, 4}, {2, 5, 5, 6, 3}, {6, 5, 6, 5, 5}, {3, 4, 2, 1, 6}, {7, 2, 2, 2, 2},
        {5, 5, 5, 5, 7}, {5, 5, 5, 5, 2}, {5, 5, 7, 7, 5}, {5, 5, 2, 5, 5}, {5, 5, 2, 2, 2},
        {7, 1, 2, 4, 7},
    };
    if (ch >= 'a' && ch <= 'z') ch = (char)(ch - 'a' + 'A');
    const char *p = strchr(chars, ch);
    if (!p || !ch) return 0;
    memcpy(bits, rows[p - chars], sizeof rows[0]);
    return 1;
}

/* Text at (x, y) top-left, 2x scale: 8 pixels per character. */
static void text(canvas *c, int x, int y, const char *s, const unsigned char rgb[3])
{
    for (; *s; s++, x += 8) {
        unsigned short bits[5];
        if (!glyph(*s, bits)) continue;
        for (int r = 0; r < 5; r++)
            for (int k = 0; k < 3; k++)
                if (bits[r] & (4 >> k))
                    for (int dy = 0; dy < 2; dy++)
                        for (int dx = 0; dx < 2; dx++) put(c, x + 2 * k + dx, y + 2 * r + dy, rgb);
    }
}

static const unsigned char palette[][3] = {
    {120, 120, 120}, {230, 140, 30}, {40, 110, 220}, {30, 160, 70}, {150, 60, 190}, {200, 40, 40},
};
#define PALETTE ((int)(sizeof palette / sizeof palette[0]))

int plot_pareto(const char *path, const plot_point *pt, int n, const char *const *legend, int series,
                const char *x_label, const char *y_label, const char *title)
{
    canvas *c = malloc(sizeof *c);
    if (!c) return -1;
    memset(c->px, 255, sizeof c->px);
    static const unsigned char ink[3] = {30, 30, 30}, grid[3] = {225, 225, 225}, front[3] = {200, 40, 40};
    /* axes: x linear from 0, y logarithmic over whole decades */
    double xmax = 1.0, ymin = 1e9, ymax = 0.0;
    for (int i = 0; i < n; i++) {
        if (pt[i].cost > xmax) xmax = pt[i].cost;
        if (pt[i].error > 0.0 && pt[i].error < ymin) ymin = pt[i].error;
        if (pt[i].error > ymax) ymax = pt[i].error;
    }
    xmax = ceil(xmax * 1.1);
    double d0 = floor(log10(ymin > 0.0 && ymin < 1e9 ? ymin : 0.01)), d1 = ceil(log10(ymax > 0.0 ? ymax : 1.0));
    if (d1 <= d0) d1 = d0 + 1.0;
    int pw = W - LEFT - RIGHT, ph = H - TOP - BOTTOM;
#define PX(v) (LEFT + (v) / xmax * pw)
#define PY(e) (TOP + ph - (log10(e) - d0) / (d1 - d0) * ph)
    for (int k = 0; k <= (int)xmax; k++) {
        double x = PX((double)k);
        line(c, x, TOP, x, TOP + ph, grid);
        char buf[16];
        snprintf(buf, sizeof buf, "%d", k);
        text(c, (int)x - 4, TOP + ph + 6, buf, ink);
    }
    for (double d = d0; d <= d1; d += 1.0) {
        double y = PY(pow(10.0, d));
        line(c, LEFT, y, LEFT + pw, y, grid);
        char buf[16];
        snprintf(buf, sizeof buf, "%g%%", 100.0 * pow(10.0, d));
        text(c, LEFT - 8 - 8 * (int)strlen(buf), (int)y - 5, buf, ink);
    }
    line(c, LEFT, TOP + ph, LEFT + pw, TOP + ph, ink);
    line(c, LEFT, TOP, LEFT, TOP + ph, ink);
    text(c, LEFT + pw / 2 - 4 * (int)strlen(x_label), H - 22, x_label, ink);
    text(c, LEFT + pw / 2 - 4 * (int)strlen(title), 4, title, ink);
    text(c, 8, 22, y_label, ink);
    /* the Pareto front: the points no other point beats in both cost and
     * error, joined in order of cost */
    int *on = calloc((size_t)n, sizeof *on), m = 0;
    int *order = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    for (int i = 0; on && order && i < n; i++) {
        int dominated = 0;
        for (int j = 0; j < n && !dominated; j++)
            if (j != i && pt[j].cost <= pt[i].cost && pt[j].error <= pt[i].error &&
                (pt[j].cost < pt[i].cost || pt[j].error < pt[i].error))
                dominated = 1;
        if (!dominated && pt[i].error > 0.0) on[i] = 1, order[m++] = i;
    }
    for (int a = 0; a < m; a++) /* insertion sort by cost: a handful of points */
        for (int b = a; b > 0 && pt[order[b]].cost < pt[order[b - 1]].cost; b--) {
            int t = order[b];
            order[b] = order[b - 1], order[b - 1] = t;
        }
    for (int a = 0; a + 1 < m; a++)
        line(c, PX(pt[order[a]].cost), PY(pt[order[a]].error), PX(pt[order[a + 1]].cost), PY(pt[order[a + 1]].error),
             front);
    for (int i = 0; i < n; i++) {
        if (!(pt[i].error > 0.0)) continue;
        disc(c, PX(pt[i].cost), PY(pt[i].error), 6.0, pt[i].hollow, palette[pt[i].series % PALETTE]);
        if (on && on[i]) disc(c, PX(pt[i].cost), PY(pt[i].error), 9.0, 1, front);
    }
    free(on);
    free(order);
    /* legend */
    int lx = W - RIGHT + 20, ly = TOP + 10;
    for (int s = 0; s < series; s++, ly += 22) {
        disc(c, lx, ly + 4, 6.0, 0, palette[s % PALETTE]);
        text(c, lx + 14, ly, legend[s], ink);
    }
    ly += 10;
    disc(c, lx, ly + 4, 6.0, 0, ink);
    text(c, lx + 14, ly, "core", ink);
    disc(c, lx, ly + 26, 6.0, 1, ink);
    text(c, lx + 14, ly + 22, "compat", ink);
    disc(c, lx, ly + 48, 9.0, 1, front);
    text(c, lx + 14, ly + 44, "pareto", ink);
#undef PX
#undef PY
    int rc = sky_write_png_rgb(path, W, H, c->px);
    free(c);
    return rc;
}

int plot_curves(const char *path, const plot_curve *cv, int n, const char *const *legend, int series, double xmin,
                double xmax, double xstep, const char *x_label, const char *y_label, const char *title)
{
    canvas *c = malloc(sizeof *c);
    if (!c) return -1;
    memset(c->px, 255, sizeof c->px);
    static const unsigned char ink[3] = {30, 30, 30}, grid[3] = {225, 225, 225};
    double ymin = 1e300, ymax = 0.0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < cv[i].n; k++)
            if (cv[i].y[k] > 0.0) ymin = fmin(ymin, cv[i].y[k]), ymax = fmax(ymax, cv[i].y[k]);
    double d0 = floor(log10(ymin < 1e300 ? ymin : 0.01)), d1 = ceil(log10(ymax > 0.0 ? ymax : 1.0));
    if (d1 <= d0) d1 = d0 + 1.0;
    int pw = W - LEFT - RIGHT, ph = H - TOP - BOTTOM;
#define PX(v) (LEFT + ((v) - xmin) / (xmax - xmin) * pw)
#define PY(e) (TOP + ph - (log10(e) - d0) / (d1 - d0) * ph)
    for (double x = xmin; x <= xmax + 1e-9; x += xstep) {
        line(c, PX(x), TOP, PX(x), TOP + ph, grid);
        char buf[16];
        snprintf(buf, sizeof buf, "%g", x);
        text(c, (int)PX(x) - 4 * (int)strlen(buf), TOP + ph + 6, buf, ink);
    }
    for (double d = d0; d <= d1; d += 1.0) {
        double y = PY(pow(10.0, d));
        line(c, LEFT, y, LEFT + pw, y, grid);
        char buf[24];
        snprintf(buf, sizeof buf, "%g", pow(10.0, d));
        text(c, LEFT - 8 - 8 * (int)strlen(buf), (int)y - 5, buf, ink);
    }
    line(c, LEFT, TOP + ph, LEFT + pw, TOP + ph, ink);
    line(c, LEFT, TOP, LEFT, TOP + ph, ink);
    text(c, LEFT + pw / 2 - 4 * (int)strlen(x_label), H - 22, x_label, ink);
    text(c, LEFT + pw / 2 - 4 * (int)strlen(title), 4, title, ink);
    text(c, 8, 22, y_label, ink);
    for (int i = 0; i < n; i++) {
        const unsigned char *rgb = palette[cv[i].series % PALETTE];
        for (int k = 0; k < cv[i].n; k++) {
            if (!(cv[i].y[k] > 0.0)) continue;
            if (cv[i].points_only) {
                disc(c, PX(cv[i].x[k]), PY(cv[i].y[k]), 6.0, 0, rgb);
            } else if (k + 1 < cv[i].n && cv[i].y[k + 1] > 0.0) {
                /* two pixels wide, so overlapping curves stay apart */
                for (int w = 0; w < 2; w++)
                    line(c, PX(cv[i].x[k]), PY(cv[i].y[k]) + w, PX(cv[i].x[k + 1]), PY(cv[i].y[k + 1]) + w, rgb);
            }
        }
    }
    int lx = W - RIGHT + 20, ly = TOP + 10;
    for (int s = 0; s < series; s++, ly += 22) {
        disc(c, lx, ly + 4, 6.0, 0, palette[s % PALETTE]);
        text(c, lx + 14, ly, legend[s], ink);
    }
#undef PX
#undef PY
    int rc = sky_write_png_rgb(path, W, H, c->px);
    free(c);
    return rc;
}
