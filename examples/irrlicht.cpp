/*
 * libsky in Irrlicht 1.8: the sky as a scene node in the sky-box pass, over a
 * small scene lit by it (sky_get_lighting), in Irrlicht's left-handed, Y-up
 * world (+x east, +z north). Options and output: examples/README.md.
 *
 * With libsky installed:
 *   g++ -std=c++11 irrlicht.cpp $(pkg-config --cflags --libs sky) \
 *       -isystem /usr/include/irrlicht -lIrrlicht -lGL -lm -o sky-irrlicht
 */
#include <irrlicht.h>
#include <GL/glx.h>
#include <sky.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace irr;

/* The sky is drawn first, into the cleared frame: the sky-box pass is
 * exactly that, after the camera and before every solid node, never culled. */
struct sky_node : scene::ISceneNode {
    sky *the_sky;
    bool right_handed;
    int result = SKY_OK; /* the last sky_draw's */
    core::aabbox3d<f32> box;
    sky_node(scene::ISceneManager *smgr, sky *s, bool rh)
        : ISceneNode(smgr->getRootSceneNode(), smgr), the_sky(s), right_handed(rh) {}
    void OnRegisterSceneNode() override
    {
        if (IsVisible)
            SceneManager->registerNodeForRendering(this, scene::ESNRP_SKY_BOX);
        ISceneNode::OnRegisterSceneNode();
    }
    void render() override
    {
        /* The camera has just set both. matrix4 is laid out as OpenGL reads
         * it, and GL_PROJECTION holds this very left-handed projection (clip
         * w = +z): the driver's one change, negating M[12], touches a zero. */
        core::matrix4 view = SceneManager->getVideoDriver()->getTransform(video::ETS_VIEW);
        core::matrix4 proj = SceneManager->getVideoDriver()->getTransform(video::ETS_PROJECTION);
        if (right_handed) {
            /* S·V·S and P·S, S = diag(1, 1, -1, 1): the same camera in a world
             * with z flipped, where the horizon frame needs no reflection. */
            const core::matrix4 S = core::matrix4().setScale(core::vector3df(1, 1, -1));
            view = S * view * S;
            proj = proj * S;
        }
        result = sky_draw(the_sky, view.pointer(), proj.pointer());
    }
    const core::aabbox3d<f32> &getBoundingBox() const override { return box; }
};

/* Irrlicht logs to stdout, which carries this program's results. */
struct log_to_stderr : IEventReceiver {
    bool OnEvent(const SEvent &e) override
    {
        if (e.EventType == EET_LOG_TEXT_EVENT && e.LogEvent.Level >= ELL_WARNING)
            std::fprintf(stderr, "irrlicht: %s\n", e.LogEvent.Text);
        return e.EventType == EET_LOG_TEXT_EVENT;
    }
};

/* Fixed-function GL writes its lit colour straight into the 8-bit frame,
 * while the sky tone-maps and gamma-encodes its own. Putting each light
 * through the sky's filmic curve (Hejl and Burgess-Dawson's, gamma
 * included) instead of the pixel is the cheap approximation that lands a
 * lit surface on the sky's scale; the albedos are sRGB colours. */
static video::SColorf tone_mapped(const float c[3], float k)
{
    auto filmic = [](float x) {
        x = std::max(x - 0.004f, 0.0f);
        return x * (6.2f * x + 0.5f) / (x * (6.2f * x + 1.7f) + 0.06f);
    };
    return video::SColorf(filmic(c[0] * k), filmic(c[1] * k), filmic(c[2] * k));
}

/* Irrlicht 1.8's createScreenShot reads the front buffer, undefined after a
 * swap (black frames under Xvfb): this reads the back buffer before endScene,
 * and writes beside the target, then renames: never a truncated PNG there. */
static bool save_frame(video::IVideoDriver *driver, const char *path)
{
    const core::dimension2d<u32> size = driver->getScreenSize();
    video::IImage *img = driver->createImage(video::ECF_R8G8B8, size);
    u8 *rows = static_cast<u8 *>(img->lock());
    for (u32 y = 0; y < size.Height; y++) /* a row at a time, as GL's run bottom-up */
        glReadPixels(0, size.Height - 1 - y, size.Width, 1, GL_RGB, GL_UNSIGNED_BYTE, rows + y * img->getPitch());
    img->unlock();
    const std::string tmp = std::string(path) + ".part.png"; /* Irrlicht's writer goes by the extension */
    const bool ok = driver->writeImageToFile(img, tmp.c_str()) && !std::rename(tmp.c_str(), path);
    img->drop();
    if (!ok)
        std::remove(tmp.c_str());
    return ok;
}

static void add_solid(scene::IMeshSceneNode *node, video::SColor albedo)
{
    video::SMaterial &m = node->getMaterial(0);
    m.ColorMaterial = video::ECM_NONE; /* take the albedo, not vertex colours */
    m.AmbientColor = m.DiffuseColor = albedo;
    m.FogEnable = true;
    m.NormalizeNormals = true; /* the boxes are scaled */
}

/* Reads s, all of it, into *out: true if it is a number in [lo, hi]. */
static bool number(const char *s, float lo, float hi, float *out)
{
    char *end;
    const double v = s ? std::strtod(s, &end) : NAN;
    *out = (float)v;
    return v >= lo && v <= hi && end != s && !*end;
}

int main(int argc, char **argv)
{
    float frames = 0, hold_time = -1; /* frames 0: interactive; hold_time < 0: the day runs */
    sky_params params = sky_default_params();
    params.cover = 0.35f; /* the README's default */
    const char *screenshot = nullptr;
    bool face_sun = false, no_sky = false, right_handed = false, no_reflection = false;
    bool ok = true;
    for (int i = 1; i < argc && ok; i++) { /* argv[i + 1] is at worst argv[argc], null */
        const std::string a = argv[i];
        if (a == "--face-sun") face_sun = true;
        else if (a == "--no-sky") no_sky = true;
        else if (a == "--right-handed") right_handed = true;
        else if (a == "--no-reflection") no_reflection = true;
        else if (a == "--screenshot" && argv[i + 1]) screenshot = argv[++i];
        else if (a == "--frames" && number(argv[i + 1], 1, 1e9f, &frames)) i++;
        else if (a == "--time" && number(argv[i + 1], 0, 1, &hold_time)) i++;
        else if (a == "--cover" && number(argv[i + 1], 0, 1, &params.cover)) i++;
        else ok = false;
    }
    const int n_frames = (int)frames;
    if (!ok || (screenshot && !n_frames) || (right_handed && no_reflection)) {
        std::fprintf(stderr, "usage: sky-irrlicht [--frames N [--screenshot FILE]] [--time T] [--cover C]\n"
                             "       [--face-sun] [--no-sky] [--right-handed | --no-reflection]\n");
        return 2;
    }

    log_to_stderr logger;
    const core::dimension2d<u32> size = n_frames ? core::dimension2d<u32>(640, 360) : core::dimension2d<u32>(1280, 720);
    IrrlichtDevice *device = createDevice(video::EDT_OPENGL, size, 16, false, false, false, &logger);
    if (!device) {
        std::fprintf(stderr, "sky-irrlicht: cannot open an OpenGL window\n");
        return 1;
    }
    video::IVideoDriver *driver = device->getVideoDriver();
    scene::ISceneManager *smgr = device->getSceneManager();

    /* Irrlicht's world is left-handed: the horizon frame's south (+z) lands
     * on world -z by a reflection, which is how libsky learns the
     * handedness of the projection it will be given. */
    const float reflect_z[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
    sky_config cfg = {};
    cfg.get_proc_address = [](const char *name) { return glXGetProcAddressARB(reinterpret_cast<const GLubyte *>(name)); };
    if (!right_handed && !no_reflection)
        std::copy(reflect_z, reflect_z + 9, cfg.horizon_to_world);
    char err[256];
    sky *s = sky_create(&cfg, err, sizeof err); /* the device's context is current */
    if (!s) {
        std::fprintf(stderr, "sky-irrlicht: sky_create: %s\n", err);
        device->drop();
        return 1;
    }
    sky_node *sky_pass = new sky_node(smgr, s, right_handed);
    sky_pass->drop(); /* the scene graph holds it */
    sky_pass->setVisible(!no_sky); /* --no-sky: lit by the sky, not drawn */

    scene::IAnimatedMesh *ground = smgr->addHillPlaneMesh("ground", {20, 20}, {20, 20}); /* 400 m square */
    add_solid(smgr->addMeshSceneNode(ground->getMesh(0)), {255, 85, 100, 65}); /* grass */
    const video::SColor stone[] = {{255, 140, 125, 110}, {255, 110, 115, 125}, {255, 150, 110, 80}};
    const float boxes[][4] = {{-6, 2, -18, 4}, {3, 1.5f, -12, 3}, {10, 4, -30, 8}, {-22, 3, -45, 6}}; /* centre; width */
    for (int i = 0; i < 4; i++) {
        const float *b = boxes[i];
        add_solid(smgr->addCubeSceneNode(1, nullptr, -1, {b[0], b[1], b[2]}, {0, 25.0f * i, 0}, {b[3], 2 * b[1], b[3]}),
                  stone[i % 3]);
    }

    /* South (-z), 8 degrees up: the horizon below the middle, the scene beneath. */
    const core::vector3df eye(0, 1.7f, 0);
    scene::ICameraSceneNode *camera =
        smgr->addCameraSceneNode(nullptr, eye, eye + core::vector3df(0, std::tan(8 * core::DEGTORAD), -1));
    camera->setFOV(60 * core::DEGTORAD);
    camera->setNearValue(0.1f);
    camera->setFarValue(1000);
    scene::ILightSceneNode *sun = smgr->addLightSceneNode();
    sun->setLightType(video::ELT_DIRECTIONAL);
    sun->getLightData().SpecularColor = video::SColorf(0, 0, 0);
    sky_lighting light;
    core::vector3df to_sun;
    bool saved = false;
    const u32 start = device->getTimer()->getRealTime();
    double clock = 0; /* seconds since the loop started */
    for (int frame = 0; device->run() && (!n_frames || frame < n_frames); frame++) {
        /* Headless runs step 1/60 s a frame, so that they repeat exactly. */
        const double now = n_frames ? frame / 60.0 : (device->getTimer()->getRealTime() - start) / 1000.0;
        sky_update(s, now - clock);
        clock = now;
        /* a day in two minutes, from 7 in the morning */
        params.time = hold_time >= 0 ? hold_time : (float)std::fmod(7 / 24.0 + clock / 120, 1.0);
        sky_set_params(s, &params);
        sky_get_lighting(s, &light);

        /* in the world libsky was told of: --right-handed flipped Irrlicht's z */
        const float *d = light.sun_direction;
        to_sun.set(d[0], d[1], right_handed ? -d[2] : d[2]);
        /* A directional light shines along its node's +z turned by its rotation. */
        sun->setRotation((-to_sun).getHorizontalAngle());
        sun->getLightData().DiffuseColor = tone_mapped(light.sun_color, light.exposure / core::PI);
        smgr->setAmbientLight(tone_mapped(light.ambient_color, light.exposure / core::PI));
        /* The sky's horizon, so distant boxes fade into it. */
        driver->setFog(tone_mapped(light.fog_color, light.exposure).toSColor(), video::EFT_FOG_LINEAR, 50, 600, 0, true);

        if (face_sun && frame == 0) {
            /* 15 degrees to the right of the sun (it sits left of the centre), 10 below it */
            const float az = std::atan2(to_sun.X, to_sun.Z) + 15 * core::DEGTORAD,
                        up = std::asin(to_sun.Y) - 10 * core::DEGTORAD;
            camera->setTarget(eye + core::vector3df(std::sin(az) * std::cos(up), std::sin(up), std::cos(az) * std::cos(up)));
        }

        driver->beginScene(true, true, video::SColor(255, 0, 0, 0));
        smgr->drawAll();
        if (screenshot && frame + 1 == n_frames)
            saved = save_frame(driver, screenshot);
        driver->endScene();
    }

    const int status = sky_pass->result < 0 || (screenshot && !saved);
    if (sky_pass->result < 0)
        std::fprintf(stderr, "sky-irrlicht: sky_draw: %s\n", sky_last_error(s));
    if (screenshot && !saved)
        std::fprintf(stderr, "sky-irrlicht: cannot write %s\n", screenshot);

    const core::dimension2d<u32> screen = driver->getScreenSize();
    const core::position2d<s32> p =
        smgr->getSceneCollisionManager()->getScreenCoordinatesFrom3DPosition(eye + to_sun * 500, camera);
    std::printf("size %u %u\n", screen.Width, screen.Height);
    if (p.X >= 0 && p.Y >= 0 && p.X < (s32)screen.Width && p.Y < (s32)screen.Height) /* behind: (-10000, -10000) */
        std::printf("sun_pixel %d %d\n", p.X, p.Y);
    else
        std::printf("sun_pixel none\n");
    std::printf("sky_draw %d\n", sky_pass->result);

    sky_destroy(s); /* while the device's context is still current */
    device->drop();
    return status;
}
