/*
 * vsopgen: writes libsky's planet tables, sky/planet_tables.c, from the
 * full VSOP87D series (P. Bretagnon and G. Francou, "Planetary theories in
 * rectangular and spherical variables: VSOP87 solutions", A&A 202, 309,
 * 1988: heliocentric ecliptic longitude L, latitude B and radius R of
 * each planet, referred to the mean ecliptic and equinox of the date), as
 * the npm package astronomia (MIT) carries them in data/vsop87D*.js.
 *
 *   vsopgen --data DIR --out planet_tables.c [--arcsec 2.0]
 *
 * The full series hold up to 5 500 terms a planet, far more than a frame
 * can evaluate; like Meeus (Astronomical Algorithms, Appendix III) the
 * tables keep the terms that matter over the dates in use. The rule here:
 * a term A cos(B + C tau) of the series multiplied by tau^alpha is kept
 * when |A| TAU_MAX^alpha >= eps (R, in au) or eps / a (L and B, in
 * radians, a the planet's mean distance), so that every dropped term moves
 * the planet by at most about eps au over 1800..2200 (|tau| <= TAU_MAX
 * millennia). For each planet the tool picks the largest eps whose
 * truncated series stay within --arcsec of the full series, seen from the
 * full series' Earth, at 4 000 instants spread over 1800..2200 (the
 * worst case is at the planet's closest approach), and prints the terms
 * kept and the error measured.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TAU_MAX 0.2 /* millennia from J2000: 1800..2200 */
#define INSTANTS 4000
#define MAX_ALPHA 6
#define ARCSEC (M_PI / 648000.0)

typedef struct term { double a, b, c; } term;
typedef struct series { term *terms; int count, cap; } series;
typedef struct body {
    const char *name;
    double mean_distance; /* au */
    series s[3][MAX_ALPHA]; /* L, B, R by power of tau */
} body;

static int parse(const char *path, body *p)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "vsopgen: cannot open %s\n", path);
        return -1;
    }
    char line[512];
    int coord = -1, alpha = -1, lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *t = line;
        while (*t == ' ') t++;
        if ((t[0] == 'L' || t[0] == 'B' || t[0] == 'R') && t[1] == ':') {
            coord = t[0] == 'L' ? 0 : (t[0] == 'B' ? 1 : 2);
            alpha = -1;
        } else if (t[0] == '"' && t[1] >= '0' && t[1] <= '9' && t[2] == '"') {
            alpha = t[1] - '0';
            if (alpha >= MAX_ALPHA || coord < 0) {
                fprintf(stderr, "vsopgen: %s:%d: unexpected series\n", path, lineno);
                fclose(f);
                return -1;
            }
        } else if (t[0] == '[' && coord >= 0 && alpha >= 0) {
            term k;
            if (sscanf(t, "[%lf, %lf, %lf]", &k.a, &k.b, &k.c) != 3) {
                fprintf(stderr, "vsopgen: %s:%d: bad term\n", path, lineno);
                fclose(f);
                return -1;
            }
            series *s = &p->s[coord][alpha];
            if (s->count == s->cap) {
                s->cap = s->cap ? 2 * s->cap : 256;
                s->terms = realloc(s->terms, sizeof(term) * (size_t)s->cap);
                if (!s->terms) {
                    fclose(f);
                    return -1;
                }
            }
            s->terms[s->count++] = k;
        }
    }
    fclose(f);
    if (!p->s[0][0].count || !p->s[1][0].count || !p->s[2][0].count) {
        fprintf(stderr, "vsopgen: %s: no L, B or R series\n", path);
        return -1;
    }
    return 0;
}

static int kept(const body *p, int coord, int alpha, const term *k, double eps)
{
    double limit = coord == 2 ? eps : eps / p->mean_distance;
    return fabs(k->a) * pow(TAU_MAX, alpha) >= limit;
}

/* L, B, R at tau; eps < 0 sums every term. */
static void evaluate(const body *p, double tau, double eps, double out[3])
{
    for (int c = 0; c < 3; c++) {
        double total = 0.0, tp = 1.0;
        for (int al = 0; al < MAX_ALPHA; al++, tp *= tau) {
            const series *s = &p->s[c][al];
            double sum = 0.0;
            for (int i = 0; i < s->count; i++)
                if (eps < 0.0 || kept(p, c, al, &s->terms[i], eps))
                    sum += s->terms[i].a * cos(s->terms[i].b + s->terms[i].c * tau);
            total += sum * tp;
        }
        out[c] = total;
    }
}

static void rectangular(const double lbr[3], double v[3])
{
    v[0] = lbr[2] * cos(lbr[1]) * cos(lbr[0]);
    v[1] = lbr[2] * cos(lbr[1]) * sin(lbr[0]);
    v[2] = lbr[2] * sin(lbr[1]);
}

static double angle(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

/* The instants: evenly over 1800..2200 with an irrational step, so every
 * synodic phase is met. */
static double instant(int i) { return -TAU_MAX + 2.0 * TAU_MAX * fmod(i * 0.6180339887498949, 1.0); }

typedef struct truth { double earth[3], full[3]; } truth;

static double worst_error(const body *p, const truth *tr, double eps)
{
    double worst = 0.0;
    for (int i = 0; i < INSTANTS; i++) {
        double lbr[3], v[3], g_full[3], g[3];
        evaluate(p, instant(i), eps, lbr);
        rectangular(lbr, v);
        for (int k = 0; k < 3; k++) {
            g_full[k] = tr[i].full[k] - tr[i].earth[k];
            g[k] = v[k] - tr[i].earth[k];
        }
        double e = angle(g_full, g);
        if (e > worst) worst = e;
    }
    return worst;
}

static int count_kept(const body *p, double eps, int coord, int alpha)
{
    int n = 0;
    const series *s = &p->s[coord][alpha];
    for (int i = 0; i < s->count; i++) n += kept(p, coord, alpha, &s->terms[i], eps);
    return n;
}

static void write_planet(FILE *out, const body *p, double eps)
{
    static const char coords[3] = {'L', 'B', 'R'};
    int top[3];
    for (int c = 0; c < 3; c++) {
        top[c] = 0;
        for (int al = 0; al < MAX_ALPHA; al++) {
            int n = count_kept(p, eps, c, al);
            if (!n) continue;
            top[c] = al + 1;
            fprintf(out, "static const sky_vsop_term %s_%c%d[%d] = {\n", p->name, coords[c], al, n);
            const series *s = &p->s[c][al];
            for (int i = 0; i < s->count; i++)
                if (kept(p, c, al, &s->terms[i], eps))
                    fprintf(out, "    {%.15g, %.15g, %.15g},\n", s->terms[i].a * 1e8, s->terms[i].b, s->terms[i].c);
            fprintf(out, "};\n");
        }
    }
    fprintf(out, "const sky_vsop_planet sky_vsop_%s = {\n    {", p->name);
    for (int c = 0; c < 3; c++) {
        fprintf(out, "%s{", c ? ",\n     " : "");
        for (int al = 0; al < top[c]; al++) {
            int n = count_kept(p, eps, c, al);
            if (n)
                fprintf(out, "%s{%s_%c%d, %d}", al ? ", " : "", p->name, coords[c], al, n);
            else
                fprintf(out, "%s{0, 0}", al ? ", " : "");
        }
        fprintf(out, "}");
    }
    fprintf(out, "},\n    {%d, %d, %d},\n};\n\n", top[0], top[1], top[2]);
}

int main(int argc, char **argv)
{
    const char *dir = NULL, *out_path = NULL;
    double arcsec = 2.0;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--data"))
            dir = argv[i + 1];
        else if (!strcmp(argv[i], "--out"))
            out_path = argv[i + 1];
        else if (!strcmp(argv[i], "--arcsec"))
            arcsec = atof(argv[i + 1]);
    }
    if (!dir || !out_path || !(arcsec > 0.0)) {
        fprintf(stderr, "usage: vsopgen --data DIR --out planet_tables.c [--arcsec 2.0]\n");
        return 2;
    }
    body bodies[] = {{"earth", 1.0, {{{0}}}},     {"mercury", 0.387, {{{0}}}}, {"venus", 0.723, {{{0}}}},
                     {"mars", 1.524, {{{0}}}},    {"jupiter", 5.203, {{{0}}}}, {"saturn", 9.537, {{{0}}}}};
    const int count = (int)(sizeof bodies / sizeof bodies[0]);
    for (int b = 0; b < count; b++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/vsop87D%s.js", dir, bodies[b].name);
        if (parse(path, &bodies[b])) return 1;
    }
    truth *tr = malloc(sizeof(truth) * INSTANTS);
    if (!tr) return 1;
    for (int i = 0; i < INSTANTS; i++) {
        double lbr[3];
        evaluate(&bodies[0], instant(i), -1.0, lbr);
        rectangular(lbr, tr[i].earth);
    }
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", out_path);
    FILE *out = fopen(tmp, "w");
    if (!out) {
        fprintf(stderr, "vsopgen: cannot write %s\n", tmp);
        return 1;
    }
    fprintf(out,
            "/*\n"
            " * Generated by tools/vsopgen.c (make planet-tables); do not edit.\n"
            " *\n"
            " * VSOP87D (P. Bretagnon and G. Francou, A&A 202, 309, 1988): heliocentric\n"
            " * ecliptic longitude L, latitude B (radians) and radius R (au) of the\n"
            " * planets, mean ecliptic and equinox of the date, as series\n"
            " * sum_alpha tau^alpha sum_k A cos(B + C tau), tau in Julian millennia TDB\n"
            " * from J2000.0. A is stored in units of 1e-8 (radian or au), as in the\n"
            " * Earth's table of astro_tables.c. Data: the npm package astronomia 4.2.0\n"
            " * (MIT), data/vsop87D*.js, which carries the full series.\n"
            " *\n"
            " * Truncated so that each planet stays within %.2g\" of the full series\n"
            " * (geocentric, 1800..2200); per planet, the terms kept and the worst\n"
            " * error measured at %d instants:\n",
            arcsec, INSTANTS);
    double eps_of[8];
    int total_of[8], full_of[8];
    double err_of[8];
    for (int b = 1; b < count; b++) {
        body *p = &bodies[b];
        for (int i = 0; i < INSTANTS; i++) {
            double lbr[3];
            evaluate(p, instant(i), -1.0, lbr);
            rectangular(lbr, tr[i].full);
        }
        double eps = 1e-4, err = 0.0;
        while (eps > 1e-12) {
            err = worst_error(p, tr, eps);
            if (err <= arcsec * ARCSEC) break;
            eps /= pow(10.0, 0.125);
        }
        int total = 0, full = 0;
        for (int c = 0; c < 3; c++)
            for (int al = 0; al < MAX_ALPHA; al++) {
                total += count_kept(p, eps, c, al);
                full += p->s[c][al].count;
            }
        eps_of[b] = eps;
        total_of[b] = total;
        full_of[b] = full;
        err_of[b] = err / ARCSEC;
        fprintf(stderr, "%-8s eps %.3g au: %d of %d terms, worst %.3f\"\n", p->name, eps, total, full, err / ARCSEC);
    }
    for (int b = 1; b < count; b++)
        fprintf(out, " *   %-8s %5d of %5d terms (eps %.2g au), %.2f\"\n", bodies[b].name, total_of[b], full_of[b],
                eps_of[b], err_of[b]);
    fprintf(out, " */\n#include \"astro_tables.h\"\n\n");
    for (int b = 1; b < count; b++) write_planet(out, &bodies[b], eps_of[b]);
    if (fclose(out) != 0) {
        fprintf(stderr, "vsopgen: writing %s failed\n", tmp);
        remove(tmp);
        return 1;
    }
    if (rename(tmp, out_path) != 0) {
        fprintf(stderr, "vsopgen: cannot rename %s to %s\n", tmp, out_path);
        remove(tmp);
        return 1;
    }
    return 0;
}
