/*
 * libsky in OpenSceneGraph 3.6: the sky is a drawable in render bin -1, so
 * it is drawn right after the clear, before the scene, in OSG's right-handed
 * Z-up world; the scene is lit by sky_get_lighting. Options and output: see
 * examples/README.md.
 *
 * With libsky installed:
 *   g++ -std=c++11 osg.cpp $(pkg-config --cflags --libs sky) -losgViewer \
 *       -losgGA -losgDB -losgUtil -losg -lOpenThreads -lGL -lm -o sky-osg
 */
#include <osg/Fog>
#include <osg/LightModel>
#include <osg/LightSource>
#include <osg/Material>
#include <osg/ShapeDrawable>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sky.h"

static const osg::Vec3d kEye(0.0, 0.0, 1.7); /* +x east, +y north, +z up */

/* libsky wants a function returning sky_gl_proc; OSG's loader returns
 * void*, which POSIX lets a function pointer be cast from (as for dlsym). */
static sky_gl_proc get_proc(const char *name)
{
    return reinterpret_cast<sky_gl_proc>(osg::getGLExtensionFuncPtr(name));
}

/* The sky as a drawable. It only draws: the frame loop updates the sky. */
struct SkyDrawable : public osg::Drawable {
    sky *s;
    mutable int result = 0; /* the last sky_draw's */
    explicit SkyDrawable(sky *created) : s(created)
    {
        setUseDisplayList(false); /* it changes every frame */
        setCullingActive(false);  /* its bound is empty: nothing to cull by */
        getOrCreateStateSet()->setRenderBinDetails(-1, "RenderBin");
    }
    void drawImplementation(osg::RenderInfo &ri) const override
    {
        /* OSG multiplies row vectors by the transpose of OpenGL's matrix,
         * so its memory (ptr(), what glLoadMatrix takes) is OpenGL's
         * column-major layout as it is. The modelview is the camera's view:
         * this drawable has no transform above it. */
        osg::Matrixf view(ri.getState()->getModelViewMatrix()), proj(ri.getState()->getProjectionMatrix());
        result = sky_draw(s, view.ptr(), proj.ptr());
        /* sky_draw puts back every GL binding and switch it touched, so
         * osg::State's cache still matches GL and needs no dirtying. */
    }
};

/* Reads back the frame, once the whole camera has drawn; the loop sets it
 * on the last frame only. The rows come bottom-up, as GL gives them;
 * osg::Image records that and its PNG writer turns them. */
struct Screenshot : public osg::Camera::DrawCallback {
    osg::ref_ptr<osg::Image> image = new osg::Image;
    void operator()(osg::RenderInfo &ri) const override
    {
        const osg::Viewport *vp = ri.getCurrentCamera()->getViewport();
        image->readPixels(vp->x(), vp->y(), vp->width(), vp->height(), GL_RGB, GL_UNSIGNED_BYTE);
    }
};

/* Fixed-function GL multiplies colours as given and the frame has no gamma
 * step, while the sky's pixels are sRGB-encoded. For a pure power law
 * encode(albedo) * encode(light) = encode(albedo * light): so sRGB albedos
 * and encoded light colours land on the sky's scale (only the cosine is not
 * encoded). Clamping stands in for the sky's tone map. */
static osg::Vec4 encode(const float c[3], float scale)
{
    osg::Vec4 v(0, 0, 0, 1);
    for (int i = 0; i < 3; ++i) v[i] = powf(fminf(fmaxf(c[i] * scale, 0.0f), 1.0f), 1.0f / 2.2f);
    return v;
}

/* A shape of one sRGB colour. */
static osg::Node *make_shape(osg::Shape *shape, float r, float g, float b)
{
    osg::ref_ptr<osg::ShapeDrawable> node = new osg::ShapeDrawable(shape);
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setAmbient(osg::Material::FRONT_AND_BACK, osg::Vec4(r, g, b, 1));
    m->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(r, g, b, 1));
    node->getOrCreateStateSet()->setAttribute(m);
    return node.release();
}

/* Compass azimuth (0 north, 90 east) and altitude, degrees, to a direction. */
static osg::Vec3d direction(double az_deg, double alt_deg)
{
    double az = osg::DegreesToRadians(az_deg), alt = osg::DegreesToRadians(alt_deg);
    return osg::Vec3d(sin(az) * cos(alt), cos(az) * cos(alt), sin(alt));
}

static int usage(const std::string &what)
{
    fprintf(stderr, "sky-osg: %s\nusage: sky-osg [--frames N [--screenshot FILE]] [--time T] "
                    "[--cover C] [--face-sun] [--no-sky]\n", what.c_str());
    return 2;
}

int main(int argc, char **argv)
{
    long frames = 0;
    const char *shot = nullptr;
    bool face_sun = false, draw_sky = true;
    float time = -1.0f; /* < 0: the day runs */
    sky_params params = sky_default_params();
    params.cover = 0.35f;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--face-sun") face_sun = true;
        else if (a == "--no-sky") draw_sky = false;
        else if (i + 1 == argc) return usage("unknown option or missing value: " + a);
        else if (a == "--screenshot") shot = argv[++i];
        else {
            const char *arg = argv[++i];
            char *end;
            double v = strtod(arg, &end);
            bool num = end != arg && !*end; /* NaN fails every range below */
            if (num && a == "--frames" && v >= 1 && v <= 1e6 && v == floor(v)) frames = (long)v;
            else if (num && a == "--time" && v >= 0 && v <= 1) time = (float)v;
            else if (num && a == "--cover" && v >= 0 && v <= 1) params.cover = (float)v;
            else return usage("bad option or value: " + a + " " + arg);
        }
    }
    if (shot && !frames) return usage("--screenshot needs --frames");

    /* The scene: ground and a few shapes south of the eye, none white. */
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(make_shape(new osg::Box(osg::Vec3(0, 0, -0.05f), 400, 400, 0.1f), 0.33f, 0.42f, 0.24f));
    root->addChild(make_shape(new osg::Box(osg::Vec3(-6, -20, 1.5f), 3), 0.62f, 0.55f, 0.48f));
    root->addChild(make_shape(new osg::Box(osg::Vec3(5, -30, 3), 4, 4, 6), 0.55f, 0.35f, 0.28f));
    root->addChild(make_shape(new osg::Sphere(osg::Vec3(1, -14, 1), 1), 0.45f, 0.50f, 0.62f));
    root->addChild(make_shape(new osg::Cylinder(osg::Vec3(-14, -40, 4), 1.5f, 8), 0.6f, 0.6f, 0.55f));

    /* The sun (or, after dark, the sky alone) lights it: one directional
     * light, the sky's irradiance as the global ambient, its horizon as fog. */
    osg::ref_ptr<osg::LightSource> sun = new osg::LightSource; /* GL_LIGHT0 */
    root->addChild(sun);
    osg::ref_ptr<osg::LightModel> lm = new osg::LightModel;
    osg::ref_ptr<osg::Fog> fog = new osg::Fog;
    fog->setMode(osg::Fog::EXP);
    fog->setDensity(1.0f / 400.0f);
    osg::StateSet *ss = root->getOrCreateStateSet();
    ss->setAttributeAndModes(lm);
    ss->setAttributeAndModes(fog);
    ss->setMode(GL_LIGHTING, osg::StateAttribute::ON);
    ss->setMode(GL_LIGHT0, osg::StateAttribute::ON);

    osgViewer::Viewer viewer;
    viewer.setSceneData(root);
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded); /* the loop needs no locks */
    viewer.setUpViewInWindow(0, 0, frames ? 640 : 1280, frames ? 360 : 720);
    osg::Camera *cam = viewer.getCamera();
    cam->setClearColor(draw_sky ? osg::Vec4(0.5f, 0.5f, 0.5f, 1) : osg::Vec4(0, 0, 0, 1));
    /* Fixed near and far: the sky has no depth worth fitting. */
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    viewer.realize();
    osg::GraphicsContext *gc = cam->getGraphicsContext();
    if (!viewer.isRealized() || !gc || !gc->makeCurrent()) {
        fprintf(stderr, "sky-osg: no OpenGL window\n");
        return 1;
    }

    /* sky_create needs the GL context current: outside a frame, ours to make so. */
    sky_config cfg = {}; /* zero: the defaults */
    cfg.get_proc_address = get_proc;
    const float z_up[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0}; /* horizon x, y (up), z: OSG's x, z, -y */
    memcpy(cfg.horizon_to_world, z_up, sizeof z_up);
    char err[256];
    sky *s = sky_create(&cfg, err, sizeof err);
    gc->releaseContext();
    if (!s) {
        fprintf(stderr, "sky-osg: sky_create: %s\n", err);
        return 1;
    }
    osg::ref_ptr<SkyDrawable> sky_drawable = new SkyDrawable(s);
    if (draw_sky) root->addChild(sky_drawable); /* --no-sky: it still lights the scene */

    osg::ref_ptr<Screenshot> screenshot = new Screenshot;
    sky_lighting l = {};
    osg::Matrixd view;
    for (long n = 0; !viewer.done() && (!frames || n < frames); ++n) {
        /* The sky's clock: headless runs step a fixed 1/60 s a frame, so
         * that they repeat exactly; interactive ones follow the real time. */
        double clock = frames ? n / 60.0 : viewer.elapsedTime();
        sky_set_elapsed(s, clock);
        /* a day in two minutes, from 7 in the morning */
        params.time = time >= 0.0f ? time : (float)fmod(7.0 / 24.0 + clock / 120.0, 1.0);
        sky_set_params(s, &params);
        sky_get_lighting(s, &l);

        cam->setProjectionMatrixAsPerspective(60.0, cam->getViewport()->aspectRatio(), 0.1, 1000.0);
        osg::Vec3d look = direction(180.0, 8.0); /* south, a little up */
        const float *d = l.sun_direction; /* its colour is 0 once it has set */
        sun->getLight()->setPosition(osg::Vec4(d[0], d[1], d[2], 0.0f));
        sun->getLight()->setDiffuse(encode(l.sun_color, l.exposure / osg::PIf));
        lm->setAmbientIntensity(encode(l.ambient_color, l.exposure / osg::PIf));
        fog->setColor(encode(l.fog_color, l.exposure));
        if (face_sun) /* 15 degrees clockwise of the sun, 10 below it */
            look = direction(osg::RadiansToDegrees(atan2(d[0], d[1])) + 15.0,
                             osg::RadiansToDegrees(asin(osg::clampBetween(d[2], -1.0f, 1.0f))) - 10.0);
        view.makeLookAt(kEye, kEye + look, osg::Vec3d(0, 0, 1));
        cam->setViewMatrix(view);
        if (shot && n == frames - 1) cam->setFinalDrawCallback(screenshot);
        viewer.frame();
    }

    /* Written under a temporary name beside the target (its extension picks
     * the plugin) and renamed when complete: a failed write never leaves a
     * truncated file at the user's path. */
    int rc = 0;
    std::string tmp = std::string(shot ? shot : "") + ".tmp.png";
    if (shot && !(osgDB::writeImageFile(*screenshot->image, tmp) && !rename(tmp.c_str(), shot))) {
        fprintf(stderr, "sky-osg: could not write %s\n", shot);
        remove(tmp.c_str());
        rc = 1;
    } else if (frames) {
        const osg::Viewport *vp = cam->getViewport();
        printf("size %d %d\n", (int)vp->width(), (int)vp->height());
        /* Where this camera puts the sun: OSG multiplies row vectors,
         * p * V * P * W, and its window origin is the bottom-left. */
        const float *d = l.sun_direction;
        osg::Vec4d win = osg::Vec4d(kEye + osg::Vec3d(d[0], d[1], d[2]) * 500.0, 1.0) * view *
                         cam->getProjectionMatrix() * vp->computeWindowMatrix();
        double x = win.x() / win.w() - vp->x(), y = vp->height() - (win.y() / win.w() - vp->y());
        bool inside = win.w() > 0.0 && x >= 0.0 && x < vp->width() && y >= 0.0 && y < vp->height();
        if (inside) printf("sun_pixel %.1f %.1f\n", x, y);
        else printf("sun_pixel none\n");
        printf("sky_draw %d\n", sky_drawable->result);
        if (sky_drawable->result < 0) {
            fprintf(stderr, "sky-osg: sky_draw: %s\n", sky_last_error(s));
            rc = 1;
        }
    }

    /* sky_destroy too needs the context current; it still exists here. */
    if (gc->makeCurrent()) {
        sky_destroy(s);
        gc->releaseContext();
    }
    return rc;
}
