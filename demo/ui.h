/*
 * sky-demo's overlay: Roden & Parberry's six sliders drawn in GL over the
 * sky, with labels and a text panel (stb_easy_font), for OpenGL 3.3 core
 * or 2.0 contexts. Input handling is plain functions so tests can drive it
 * with synthetic events.
 */
#ifndef SKY_DEMO_UI_H
#define SKY_DEMO_UI_H

#include "sky.h"

typedef struct ui ui;

/* The overlay's context: OpenGL 2.0 (GLSL 1.10), 3.3 core (GLSL 330, a
 * VAO of its own) or OpenGL ES 2.0 (GLSL ES 1.00). */
enum { UI_GL20 = 0, UI_CORE33 = 1, UI_ES20 = 2 };
ui *ui_create(int kind);
void ui_destroy(ui *u);

/* Slider geometry, in window pixels from the top left. */
#define UI_SLIDER_X 100.0f
#define UI_SLIDER_W 220.0f
#define UI_SLIDER_Y0 20.0f
#define UI_SLIDER_DY 22.0f
#define UI_SLIDER_H 12.0f

/* Mouse input: returns 1 if the overlay took the event. The six values are
 * the sliders in sky_params order. */
int ui_mouse_button(ui *u, int pressed, double x, double y, float values[6], int *selected);
int ui_mouse_move(ui *u, double x, double y, float values[6]);

/* Draws the sliders and the text lines (NUL-separated in `text`, drawn
 * top-right) into a viewport of w x h pixels. */
void ui_draw(ui *u, int w, int h, const float values[6], int selected, const char *text);

#endif
