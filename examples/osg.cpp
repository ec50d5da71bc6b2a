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
#include <osg/Geode>
#include <osg/Light>
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
 * void*. Copying the bits is the conversion POSIX guarantees (dlsym). */
static sky_gl_proc get_proc(const char *name)
{
    void *p = osg::getGLExtensionFuncPtr(name);
    sky_gl_proc f;
    memcpy(&f, &p, sizeof f);
    return f;
}

/* What the sky drawable and the frame loop share. The viewer runs single
 * threaded, so the loop reads these between frames without locking. */
struct SkyState {
    sky *s = nullptr;
    bool failed = false, draw = true, hold = false, lit = false; /* lit: light is valid */
    float time = 7.0f / 24.0f, cover = 0.35f;
    double last_sim = -1.0;
    int result = 0;
    sky_lighting light;
};

class SkyDrawable : public osg::Drawable {
public:
    explicit SkyDrawable(SkyState *st) : st_(st)
    {
        setUseDisplayList(false); /* it changes every frame */
        setCullingActive(false);  /* it has no bound worth culling against */
    }
    /* Built in the draw because sky_create needs the GL context current;
     * everything per frame is here too, so the sun it draws is the sun the
     * loop reads afterwards. */
    void drawImplementation(osg::RenderInfo &ri) const override
    {
        if (st_->failed) return;
        osg::State &state = *ri.getState();
        if (!st_->s) {
            sky_config cfg = {}; /* zero: the defaults */
            cfg.get_proc_address = get_proc;
            const float z_up[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
            memcpy(cfg.horizon_to_world, z_up, sizeof z_up);
            char err[256];
            st_->s = sky_create(&cfg, err, sizeof err);
            if (!st_->s) {
                fprintf(stderr, "sky-osg: sky_create: %s\n", err);
                st_->failed = true;
                return;
            }
        }
        double now = state.getFrameStamp()->getSimulationTime();
        sky_update(st_->s, st_->last_sim < 0.0 ? 0.0 : fmax(now - st_->last_sim, 0.0));
        st_->last_sim = now;
        sky_params p = sky_default_params();
        p.cover = st_->cover;
        /* a day in two minutes */
        p.time = st_->hold ? st_->time : (float)fmod(st_->time + now / 120.0, 1.0);
        sky_set_params(st_->s, &p);
        st_->lit = sky_get_lighting(st_->s, &st_->light) >= 0;
        if (!st_->draw) return;
        /* OSG multiplies row vectors by the transpose of OpenGL's matrix,
         * so its memory (ptr(), what glLoadMatrix takes) is OpenGL's
         * column-major layout as it is. The modelview is the camera's view:
         * this drawable has no transform above it. */
        osg::Matrixf view(state.getModelViewMatrix()), proj(state.getProjectionMatrix());
        st_->result = sky_draw(st_->s, view.ptr(), proj.ptr());
        /* sky_draw puts back every GL binding and switch it touched, so
         * osg::State's cache still matches GL and needs no dirtying. */
    }
    /* An empty box: nothing to cull by, nothing to fit near and far to. */
    osg::BoundingBox computeBoundingBox() const override { return osg::BoundingBox(); }

private:
    SkyState *st_;
};

/* Reads back the frame it is armed for, once the whole camera has drawn.
 * The rows come bottom-up, as GL gives them; osg::Image records that and
 * its PNG writer turns them. */
struct Screenshot : public osg::Camera::DrawCallback {
    mutable bool armed = false;
    osg::ref_ptr<osg::Image> image = new osg::Image;
    void operator()(osg::RenderInfo &ri) const override
    {
        const osg::Viewport *vp = ri.getCurrentCamera()->getViewport();
        if (armed) image->readPixels(vp->x(), vp->y(), vp->width(), vp->height(), GL_RGB, GL_UNSIGNED_BYTE);
        armed = false;
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

static osg::Node *make_shape(osg::Shape *shape, const osg::Vec4 &srgb)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(new osg::ShapeDrawable(shape));
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setAmbient(osg::Material::FRONT_AND_BACK, srgb);
    m->setDiffuse(osg::Material::FRONT_AND_BACK, srgb);
    geode->getOrCreateStateSet()->setAttribute(m);
    return geode.release();
}

/* Compass azimuth (0 north, 90 east) and altitude, degrees, to a direction. */
static osg::Vec3d direction(double az_deg, double alt_deg)
{
    double az = osg::DegreesToRadians(az_deg), alt = osg::DegreesToRadians(alt_deg);
    return osg::Vec3d(sin(az) * cos(alt), cos(az) * cos(alt), sin(alt));
}

static int usage(const char *what)
{
    fprintf(stderr, "sky-osg: %s\nusage: sky-osg [--frames N [--screenshot FILE]] [--time T] "
                    "[--cover C] [--face-sun] [--no-sky]\n", what);
    return 2;
}

int main(int argc, char **argv)
{
    SkyState st;
    long frames = 0;
    const char *shot = nullptr;
    bool face_sun = false;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--face-sun") face_sun = true;
        else if (a == "--no-sky") st.draw = false;
        else if (i + 1 == argc) return usage(("unknown option or missing value: " + a).c_str());
        else if (a == "--screenshot") shot = argv[++i];
        else {
            const char *arg = argv[++i];
            char *end;
            double v = strtod(arg, &end);
            bool num = end != arg && !*end && !std::isnan(v);
            if (num && a == "--frames" && v >= 1 && v <= 1e6 && v == floor(v)) frames = (long)v;
            else if (num && a == "--time" && v >= 0 && v <= 1) st.time = (float)v, st.hold = true;
            else if (num && a == "--cover" && v >= 0 && v <= 1) st.cover = (float)v;
            else return usage(("bad option or value: " + a + " " + arg).c_str());
        }
    }
    if (shot && !frames) return usage("--screenshot needs --frames");

    /* The sky, drawn before everything else (bin -1) and never culled. */
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> sky_geode = new osg::Geode;
    sky_geode->addDrawable(new SkyDrawable(&st));
    sky_geode->setCullingActive(false);
    sky_geode->getOrCreateStateSet()->setRenderBinDetails(-1, "RenderBin");
    root->addChild(sky_geode);
    /* The scene: ground and a few shapes south of the eye, none white. */
    root->addChild(make_shape(new osg::Box(osg::Vec3(0, 0, -0.05f), 400, 400, 0.1f),
                              osg::Vec4(0.33f, 0.42f, 0.24f, 1)));
    root->addChild(make_shape(new osg::Box(osg::Vec3(-6, -20, 1.5f), 3), osg::Vec4(0.62f, 0.55f, 0.48f, 1)));
    root->addChild(make_shape(new osg::Box(osg::Vec3(5, -30, 3), 4, 4, 6), osg::Vec4(0.55f, 0.35f, 0.28f, 1)));
    root->addChild(make_shape(new osg::Sphere(osg::Vec3(1, -14, 1), 1), osg::Vec4(0.45f, 0.50f, 0.62f, 1)));
    root->addChild(make_shape(new osg::Cylinder(osg::Vec3(-14, -40, 4), 1.5f, 8), osg::Vec4(0.6f, 0.6f, 0.55f, 1)));

    /* The sun (or, after dark, the sky alone) lights it: one directional
     * light, the sky's irradiance as the global ambient, its horizon as fog. */
    osg::ref_ptr<osg::LightSource> sun = new osg::LightSource;
    osg::Light *light = sun->getLight(); /* GL_LIGHT0 */
    root->addChild(sun);
    osg::ref_ptr<osg::LightModel> lm = new osg::LightModel;
    osg::ref_ptr<osg::Fog> fog = new osg::Fog;
    osg::StateSet *ss = root->getOrCreateStateSet();
    fog->setMode(osg::Fog::EXP);
    fog->setDensity(1.0f / 400.0f);
    ss->setAttributeAndModes(lm);
    ss->setAttributeAndModes(fog);
    ss->setMode(GL_LIGHTING, osg::StateAttribute::ON);
    ss->setMode(GL_LIGHT0, osg::StateAttribute::ON);

    osgViewer::Viewer viewer;
    viewer.setSceneData(root);
    /* Single threaded: the frame loop reads what the draw left behind. */
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    viewer.setUpViewInWindow(0, 0, frames ? 640 : 1280, frames ? 360 : 720);
    osg::Camera *cam = viewer.getCamera();
    cam->setClearColor(st.draw ? osg::Vec4(0.5f, 0.5f, 0.5f, 1) : osg::Vec4(0, 0, 0, 1));
    /* Fixed near and far: the sky has no depth worth fitting. */
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    osg::ref_ptr<Screenshot> screenshot = new Screenshot;
    if (shot) cam->setFinalDrawCallback(screenshot);
    viewer.realize();
    if (!viewer.isRealized()) {
        fprintf(stderr, "sky-osg: no OpenGL window\n");
        return 1;
    }

    osg::Matrixd view;
    /* The first frame creates the sky, so only from the second on are its
     * lighting and sun known: that first frame is not counted. */
    for (long n = 0; !viewer.done() && !st.failed && (!frames || n < frames);) {
        const osg::Viewport *vp = cam->getViewport();
        cam->setProjectionMatrixAsPerspective(60.0, vp->width() / vp->height(), 0.1, 1000.0);
        osg::Vec3d look = direction(180.0, 8.0); /* south, a little up */
        if (st.lit) {
            const sky_lighting &l = st.light;
            const float *d = l.sun_direction; /* its colour is 0 once it has set */
            light->setPosition(osg::Vec4(d[0], d[1], d[2], 0.0f));
            light->setDiffuse(encode(l.sun_color, l.exposure / osg::PIf));
            lm->setAmbientIntensity(encode(l.ambient_color, l.exposure / osg::PIf));
            fog->setColor(encode(l.fog_color, l.exposure));
            if (face_sun) /* 15 degrees clockwise of the sun, 10 below it */
                look = direction(osg::RadiansToDegrees(atan2(d[0], d[1])) + 15.0,
                                 osg::RadiansToDegrees(asin(osg::clampBetween(d[2], -1.0f, 1.0f))) - 10.0);
        }
        view.makeLookAt(kEye, kEye + look, osg::Vec3d(0, 0, 1));
        cam->setViewMatrix(view);
        bool counted = st.s != nullptr;
        screenshot->armed = shot && counted && n == frames - 1;
        viewer.frame();
        n += counted;
    }

    /* Written under a temporary name beside the target (its extension picks
     * the plugin) and renamed when complete: a failed write never leaves a
     * truncated file at the user's path. */
    int rc = st.failed ? 1 : 0;
    std::string tmp = std::string(shot ? shot : "") + ".tmp.png";
    if (!rc && shot && !(osgDB::writeImageFile(*screenshot->image, tmp) && !rename(tmp.c_str(), shot))) {
        fprintf(stderr, "sky-osg: could not write %s\n", shot);
        remove(tmp.c_str());
        rc = 1;
    } else if (!rc && frames) {
        const osg::Viewport *vp = cam->getViewport();
        printf("size %d %d\n", (int)vp->width(), (int)vp->height());
        /* Where this camera puts the sun: OSG multiplies row vectors,
         * p * V * P * W, and its window origin is the bottom-left. */
        const float *d = st.light.sun_direction;
        osg::Vec4d clip = osg::Vec4d(kEye + osg::Vec3d(d[0], d[1], d[2]) * 500.0, 1.0) * view *
                          cam->getProjectionMatrix();
        osg::Vec3d win = osg::Vec3d(clip.x(), clip.y(), clip.z()) / clip.w() * vp->computeWindowMatrix();
        double x = win.x() - vp->x(), y = vp->height() - (win.y() - vp->y());
        if (st.lit && clip.w() > 0.0 && x >= 0.0 && x < vp->width() && y >= 0.0 && y < vp->height())
            printf("sun_pixel %.1f %.1f\n", x, y);
        else
            printf("sun_pixel none\n");
        printf("sky_draw %d\n", st.result);
        if (st.result < 0) {
            fprintf(stderr, "sky-osg: sky_draw: %s\n", sky_last_error(st.s));
            rc = 1;
        }
    }

    /* sky_destroy needs the sky's context current; it still exists here. */
    osg::GraphicsContext *gc = cam->getGraphicsContext();
    if (st.s && gc && gc->makeCurrent()) {
        sky_destroy(st.s);
        gc->releaseContext();
    }
    return rc;
}
