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
#include <cstring>
#include <string>

using namespace irr;

static sky_gl_proc get_proc(const char *name)
{
    return glXGetProcAddressARB(reinterpret_cast<const GLubyte *>(name));
}

struct options {
    int frames = 0;                   /* 0: interactive, until the window closes */
    const char *screenshot = nullptr;
    float time = -1, cover = 0.35f;   /* time < 0: the day runs */
    bool face_sun = false, no_sky = false, right_handed = false, no_reflection = false;
};

/* The sky is drawn first, into the cleared frame: the sky-box pass is
 * exactly that, after the camera and before every solid node. */
struct sky_node : scene::ISceneNode {
    sky *the_sky;
    const options &opt;
    int result = SKY_OK; /* the last sky_draw's */
    core::aabbox3d<f32> box;
    sky_node(scene::ISceneManager *smgr, sky *s, const options &o)
        : ISceneNode(smgr->getRootSceneNode(), smgr), the_sky(s), opt(o)
    {
        setAutomaticCulling(scene::EAC_OFF); /* it surrounds the camera */
    }
    void OnRegisterSceneNode() override
    {
        if (IsVisible)
            SceneManager->registerNodeForRendering(this, scene::ESNRP_SKY_BOX);
        ISceneNode::OnRegisterSceneNode();
    }
    void render() override
    {
        if (opt.no_sky)
            return;
        video::IVideoDriver *driver = SceneManager->getVideoDriver();
        /* The camera has just set both. matrix4 is laid out as OpenGL reads
         * it, and GL_PROJECTION holds this very left-handed projection (clip
         * w = +z): the driver's one change, negating M[12], touches a zero. */
        core::matrix4 view = driver->getTransform(video::ETS_VIEW);
        core::matrix4 proj = driver->getTransform(video::ETS_PROJECTION);
        if (opt.right_handed) {
            /* S V S and P S, S = diag(1, 1, -1, 1): the same camera in a world
             * with z flipped, where the horizon frame needs no reflection. */
            for (int i : {2, 6, 14, 8, 9, 11}) /* row 2 or column 2, not both */
                view[i] = -view[i];
            for (int i = 8; i < 12; i++) /* column 2 */
                proj[i] = -proj[i];
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
static float filmic(float x)
{
    x = std::max(x - 0.004f, 0.0f);
    return x * (6.2f * x + 0.5f) / (x * (6.2f * x + 1.7f) + 0.06f);
}

static video::SColorf tone_mapped(const float c[3], float k)
{
    return video::SColorf(filmic(c[0] * k), filmic(c[1] * k), filmic(c[2] * k));
}

/* Irrlicht 1.8's createScreenShot reads the front buffer, undefined after a
 * swap (black frames under Xvfb): read the back buffer before endScene. */
static video::IImage *grab_frame(video::IVideoDriver *driver)
{
    const core::dimension2d<u32> size = driver->getScreenSize();
    video::IImage *img = driver->createImage(video::ECF_R8G8B8, size);
    u8 *rows = static_cast<u8 *>(img->lock());
    GLint align;
    glGetIntegerv(GL_PACK_ALIGNMENT, &align);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.Width, size.Height, GL_RGB, GL_UNSIGNED_BYTE, rows);
    glPixelStorei(GL_PACK_ALIGNMENT, align);
    for (u32 y = 0, pitch = img->getPitch(); y < size.Height / 2; y++) /* GL's rows run bottom-up */
        std::swap_ranges(rows + y * pitch, rows + (y + 1) * pitch, rows + (size.Height - 1 - y) * pitch);
    img->unlock();
    return img;
}

static scene::IMeshSceneNode *add_solid(scene::IMeshSceneNode *node, video::SColor albedo)
{
    video::SMaterial &m = node->getMaterial(0);
    m.ColorMaterial = video::ECM_NONE; /* take the albedo, not vertex colours */
    m.AmbientColor = m.DiffuseColor = albedo;
    m.FogEnable = true;
    m.NormalizeNormals = true; /* the boxes are scaled */
    return node;
}

static bool number(const char *s, float lo, float hi, float *out)
{
    char *end;
    double v = s ? std::strtod(s, &end) : 0.0;
    if (!s || end == s || *end || !(v >= lo && v <= hi))
        return false;
    *out = (float)v;
    return true;
}

int main(int argc, char **argv)
{
    options opt;
    float frames = 0;
    bool ok = true;
    for (int i = 1; i < argc && ok; i++) {
        const std::string a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : nullptr;
        if (a == "--face-sun") opt.face_sun = true;
        else if (a == "--no-sky") opt.no_sky = true;
        else if (a == "--right-handed") opt.right_handed = true;
        else if (a == "--no-reflection") opt.no_reflection = true;
        else if (a == "--screenshot" && value) opt.screenshot = argv[++i];
        else if (a == "--frames" && number(value, 1, 1e9f, &frames)) i++;
        else if (a == "--time" && number(value, 0, 1, &opt.time)) i++;
        else if (a == "--cover" && number(value, 0, 1, &opt.cover)) i++;
        else ok = false;
    }
    opt.frames = (int)frames;
    if (!ok || (opt.screenshot && !opt.frames) || (opt.right_handed && opt.no_reflection)) {
        std::fprintf(stderr, "usage: sky-irrlicht [--frames N [--screenshot FILE]] [--time T] [--cover C]\n"
                             "       [--face-sun] [--no-sky] [--right-handed | --no-reflection]\n");
        return 2;
    }

    log_to_stderr logger;
    SIrrlichtCreationParameters dp;
    dp.DriverType = video::EDT_OPENGL;
    dp.WindowSize = opt.frames ? core::dimension2d<u32>(640, 360) : core::dimension2d<u32>(1280, 720);
    dp.EventReceiver = &logger;
    IrrlichtDevice *device = createDeviceEx(dp);
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
    sky_config cfg;
    std::memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = get_proc;
    if (!opt.right_handed && !opt.no_reflection)
        std::memcpy(cfg.horizon_to_world, reflect_z, sizeof reflect_z);
    char err[256];
    sky *s = sky_create(&cfg, err, sizeof err); /* the device's context is current */
    if (!s) {
        std::fprintf(stderr, "sky-irrlicht: sky_create: %s\n", err);
        device->drop();
        return 1;
    }
    sky_node *sky_pass = new sky_node(smgr, s, opt);
    sky_pass->drop(); /* the scene graph holds it */

    const video::SColor grass(255, 85, 100, 65), stone[] = {
        video::SColor(255, 140, 125, 110), video::SColor(255, 110, 115, 125), video::SColor(255, 150, 110, 80)};
    scene::IAnimatedMesh *ground = smgr->addHillPlaneMesh("ground", {20, 20}, {20, 20}); /* 400 m square */
    add_solid(smgr->addMeshSceneNode(ground->getMesh(0)), grass);
    const float boxes[][4] = {{-6, 2, -18, 4}, {3, 1.5f, -12, 3}, {10, 4, -30, 8}, {-22, 3, -45, 6}};
    for (int i = 0; i < 4; i++) {
        const float *b = boxes[i];
        add_solid(smgr->addCubeSceneNode(1, nullptr, -1, core::vector3df(b[0], b[1], b[2]),
                                         core::vector3df(0, 25.0f * i, 0), core::vector3df(b[3], 2 * b[1], b[3])),
                  stone[i % 3]);
    }

    /* South (-z), 8 degrees up: the horizon below the middle, the scene beneath. */
    const core::vector3df eye(0, 1.7f, 0);
    scene::ICameraSceneNode *camera =
        smgr->addCameraSceneNode(nullptr, eye, eye + core::vector3df(0, std::tan(8 * core::DEGTORAD), -1));
    camera->setFOV(60 * core::DEGTORAD);
    camera->setAspectRatio((f32)dp.WindowSize.Width / dp.WindowSize.Height);
    camera->setNearValue(0.1f);
    camera->setFarValue(1000);
    scene::ILightSceneNode *sun = smgr->addLightSceneNode();
    sun->setLightType(video::ELT_DIRECTIONAL);
    sun->getLightData().SpecularColor = video::SColorf(0, 0, 0);
    sky_params params = sky_default_params();
    params.cover = opt.cover;
    sky_lighting light;
    core::vector3df to_sun;
    video::IImage *shot = nullptr;
    ITimer *timer = device->getTimer();
    u32 last = timer->getRealTime();
    double clock = 0; /* seconds since the first frame */
    for (int frame = 0; device->run() && (!opt.frames || frame < opt.frames); frame++) {
        /* Headless runs step 1/60 s a frame, so that they repeat exactly. */
        const u32 now = timer->getRealTime();
        const double dt = frame == 0 ? 0 : opt.frames ? 1 / 60.0 : (now - last) / 1000.0;
        last = now;
        clock += dt;
        sky_update(s, dt);
        /* a day in two minutes, from 7 in the morning */
        params.time = opt.time >= 0 ? opt.time : (float)std::fmod(7 / 24.0 + clock / 120, 1.0);
        sky_set_params(s, &params);
        sky_get_lighting(s, &light);

        /* in the world libsky was told of: --right-handed flipped Irrlicht's z */
        const float *d = light.sun_direction;
        to_sun.set(d[0], d[1], opt.right_handed ? -d[2] : d[2]);
        /* A directional light shines along its node's +z turned by its rotation. */
        sun->setRotation((-to_sun).getHorizontalAngle());
        sun->getLightData().DiffuseColor = tone_mapped(light.sun_color, light.exposure / core::PI);
        smgr->setAmbientLight(tone_mapped(light.ambient_color, light.exposure / core::PI));
        /* The sky's horizon, so distant boxes fade into it. */
        driver->setFog(tone_mapped(light.fog_color, light.exposure).toSColor(), video::EFT_FOG_LINEAR, 50, 600, 0, true);

        if (opt.face_sun && frame == 0) {
            /* 15 degrees clockwise from the sun seen from above (the sun left
             * of the centre) and 10 degrees below it. */
            const float az = std::atan2(to_sun.X, to_sun.Z) + 15 * core::DEGTORAD,
                        up = std::asin(to_sun.Y) - 10 * core::DEGTORAD;
            camera->setTarget(eye + core::vector3df(std::sin(az) * std::cos(up), std::sin(up), std::cos(az) * std::cos(up)));
        }

        driver->beginScene(true, true, video::SColor(255, 0, 0, 0));
        smgr->drawAll();
        if (opt.screenshot && frame + 1 == opt.frames)
            shot = grab_frame(driver);
        driver->endScene();
    }

    int status = sky_pass->result < 0;
    if (status)
        std::fprintf(stderr, "sky-irrlicht: sky_draw: %s\n", sky_last_error(s));
    if (opt.screenshot) {
        /* Written beside the target and renamed: never a truncated PNG at
         * the user's path. Irrlicht picks the writer by the extension. */
        std::string tmp = std::string(opt.screenshot) + ".part.png";
        ok = shot && driver->writeImageToFile(shot, tmp.c_str()) && !std::rename(tmp.c_str(), opt.screenshot);
        if (shot)
            shot->drop();
        if (!ok) {
            std::remove(tmp.c_str());
            std::fprintf(stderr, "sky-irrlicht: cannot write %s\n", opt.screenshot);
            status = 1;
        }
    }

    const core::dimension2d<u32> size = driver->getScreenSize();
    const core::position2d<s32> p =
        smgr->getSceneCollisionManager()->getScreenCoordinatesFrom3DPosition(eye + to_sun * 500, camera);
    std::printf("size %u %u\n", size.Width, size.Height);
    if (p.X >= 0 && p.Y >= 0 && p.X < (s32)size.Width && p.Y < (s32)size.Height) /* behind: (-10000, -10000) */
        std::printf("sun_pixel %d %d\n", p.X, p.Y);
    else
        std::printf("sun_pixel none\n");
    std::printf("sky_draw %d\n", sky_pass->result);

    sky_destroy(s); /* while the device's context is still current */
    device->drop();
    return status;
}
