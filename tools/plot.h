/*
 * sky-bench's error-against-run-time chart: a scatter of (cost, error)
 * points with their Pareto front, written as a PNG with a built-in 3x5
 * pixel font (no font library for one chart).
 */
#ifndef SKY_PLOT_H
#define SKY_PLOT_H

typedef struct plot_point {
    double cost;        /* x: frame time over the baseline              */
    double error;       /* y: mean relative luminance error, 0..        */
    int series;         /* colour: index into the legend                */
    int hollow;         /* 1: drawn as a ring (the compat profile)      */
} plot_point;

/* Writes the chart; legend[i] names series i (count series). The y axis
 * is logarithmic. Returns 0, or -1 when the file cannot be written. */
int plot_pareto(const char *path, const plot_point *points, int n, const char *const *legend, int series,
                const char *x_label, const char *y_label, const char *title);

/* A polyline (or, with points_only, its points as discs) in series'
 * colour. */
typedef struct plot_curve {
    const double *x, *y;
    int n;
    int series;
    int points_only;
} plot_curve;

/* Writes a chart of curves: x linear over xmin..xmax with a grid line
 * every xstep, y logarithmic over the whole decades the data span (points
 * at or below 0 are left out). legend[i] names series i. Returns 0, or -1
 * when the file cannot be written. */
int plot_curves(const char *path, const plot_curve *curves, int n, const char *const *legend, int series,
                double xmin, double xmax, double xstep, const char *x_label, const char *y_label, const char *title);

#endif
