/*
 * sky-demo: the sky in a GLFW window, steered by Roden & Parberry's six
 * parameters. Keys: 1-6 pick a slider, Up/Down (or +/-) move it, Space runs
 * the time of day, F toggles the fisheye view, arrows-left/right turn the
 * camera, S saves a screenshot (sky-demo.png), Esc quits.
 * Without a display it says so and renders headless through OSMesa.
 */
#include "cli.h"
#include "osmesa_ctx.h"

#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int headless(const sky_cli *cli)
{
    char err[512];
    sky_osmesa ctx;
    const char *out = cli->screenshot ? cli->screenshot : "build/sky.png";
    if (sky_osmesa_create(&ctx, cli->width, cli->height, cli->gl, 0, err, sizeof err)) {
        fprintf(stderr, "sky-demo: %s\n", err);
        return 1;
    }
    sky_config cfg = sky_cli_config(cli, sky_osmesa_loader());
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-demo: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return 1;
    }
    float view[16], proj[16];
    sky_cli_camera(cli, view, proj);
    sky_set_params(s, &cli->params);
    sky_set_observer(s, &cli->observer);
    sky_set_elapsed(s, cli->seconds);
    int rc = 0;
    for (int f = 0; f < cli->frames && !rc; f++) {
        if (f) sky_update(s, 1.0 / 30.0);
        if ((cli->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) < 0) {
            fprintf(stderr, "sky-demo: %s\n", sky_last_error(s));
            rc = 1;
        }
    }
    sky_osmesa_finish(&ctx);
    if (!rc && sky_osmesa_write_png(&ctx, out)) {
        fprintf(stderr, "sky-demo: cannot write %s\n", out);
        rc = 1;
    }
    if (!rc) printf("sky-demo: no display; rendered %s headless\n", out);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

typedef struct demo {
    sky_cli cli;
    int slider;       /* 0..5 */
    int running;      /* time of day advancing */
    int save;
} demo;

static float *slider_value(sky_params *p, int i)
{
    float *v[6] = {&p->cover, &p->height, &p->density, &p->sunset, &p->speed, &p->time};
    return v[i];
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    demo *d = glfwGetWindowUserPointer(w);
    if (action == GLFW_RELEASE) return;
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_6) d->slider = key - GLFW_KEY_1;
    float *v = slider_value(&d->cli.params, d->slider);
    if (key == GLFW_KEY_UP || key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) *v = *v + 0.02f > 1.0f ? 1.0f : *v + 0.02f;
    if (key == GLFW_KEY_DOWN || key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) *v = *v - 0.02f < 0.0f ? 0.0f : *v - 0.02f;
    if (key == GLFW_KEY_LEFT) d->cli.yaw -= 5.0;
    if (key == GLFW_KEY_RIGHT) d->cli.yaw += 5.0;
    if (key == GLFW_KEY_SPACE) d->running = !d->running;
    if (key == GLFW_KEY_F) d->cli.fisheye = !d->cli.fisheye;
    if (key == GLFW_KEY_S) d->save = 1;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, 1);
}

static void save_screenshot(int width, int height, const char *path)
{
    sky_osmesa fake = {0};
    fake.width = width;
    fake.height = height;
    fake.pixels = malloc((size_t)width * (size_t)height * 4u);
    if (!fake.pixels) return;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, fake.pixels);
    if (sky_osmesa_write_png(&fake, path))
        fprintf(stderr, "sky-demo: cannot write %s\n", path);
    else
        printf("sky-demo: saved %s\n", path);
    free(fake.pixels);
}

int main(int argc, char **argv)
{
    demo d;
    memset(&d, 0, sizeof d);
    char err[512];
    int rc = sky_cli_parse(&d.cli, argc, argv, 1, err, sizeof err);
    if (rc == SKY_CLI_HELP) {
        sky_cli_usage(stdout, "sky-demo", 1);
        return 0;
    }
    if (rc) {
        fprintf(stderr, "sky-demo: %s\n", err);
        return 2;
    }
    int automated = d.cli.screenshot != NULL;
    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        fprintf(stderr, "sky-demo: no display found (DISPLAY is unset)\n");
        return headless(&d.cli);
    }
    if (!glfwInit()) {
        fprintf(stderr, "sky-demo: GLFW cannot open the display\n");
        return headless(&d.cli);
    }
    GLFWwindow *win = NULL;
    if (d.cli.gl != SKY_GL_COMPAT20) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        win = glfwCreateWindow(d.cli.width, d.cli.height, "libsky", NULL, NULL);
    }
    if (!win) {
        glfwDefaultWindowHints();
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
        win = glfwCreateWindow(d.cli.width, d.cli.height, "libsky", NULL, NULL);
    }
    if (!win) {
        fprintf(stderr, "sky-demo: no GL window could be created\n");
        glfwTerminate();
        return headless(&d.cli);
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(win, &d);
    glfwSetKeyCallback(win, on_key);
    sky_config cfg = sky_cli_config(&d.cli, glfwGetProcAddress);
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "sky-demo: %s\n", err);
        glfwTerminate();
        return 1;
    }
    sky_set_observer(s, &d.cli.observer);
    sky_set_elapsed(s, d.cli.seconds);
    double last = glfwGetTime();
    int frame = 0;
    while (!glfwWindowShouldClose(win)) {
        double now = glfwGetTime();
        double dt = automated ? 1.0 / 30.0 : now - last;
        last = now;
        if (d.running) d.cli.params.time = (float)(d.cli.params.time + dt / 60.0 - (int)(d.cli.params.time + dt / 60.0));
        sky_set_params(s, &d.cli.params);
        sky_update(s, dt);
        int fw, fh;
        glfwGetFramebufferSize(win, &fw, &fh);
        glViewport(0, 0, fw, fh);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        d.cli.width = fw > 0 ? fw : 1;
        d.cli.height = fh > 0 ? fh : 1;
        float view[16], proj[16];
        sky_cli_camera(&d.cli, view, proj);
        if ((d.cli.fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) < 0)
            fprintf(stderr, "sky-demo: %s\n", sky_last_error(s));
        frame++;
        if (d.save || (automated && frame >= d.cli.frames)) {
            save_screenshot(fw, fh, automated ? d.cli.screenshot : "sky-demo.png");
            d.save = 0;
            if (automated) break;
        }
        char title[160];
        const sky_params *p = &d.cli.params;
        snprintf(title, sizeof title, "libsky  [%d] cover %.2f height %.2f density %.2f sunset %.2f speed %.2f time %.2f",
                 d.slider + 1, p->cover, p->height, p->density, p->sunset, p->speed, p->time);
        glfwSetWindowTitle(win, title);
        glfwSwapBuffers(win);
        glfwPollEvents();
    }
    sky_destroy(s);
    glfwDestroyWindow(win);
    glfwTerminate();
    return 0;
}
