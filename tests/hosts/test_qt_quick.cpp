/* The Qt Quick integration (integrations/qt/, docs/hosts/qt-quick.md) in a real Qt Quick window:
 * xcb on Xvfb (tests/hosts/qt_quick.sh runs it under xvfb-run; the VM tier runs the smaller item
 * on eglfs on vkms, tests/vm/guest.sh), OpenGL ES 3.0 asked for as a user does, the basic render
 * loop so that each grabWindow() is one frame.
 *
 * A QML scene with a background, the SbfxItem, and an opaque rectangle with text above it, once
 * with the item filling the window (sbfx composites into Qt's framebuffer) and once smaller than
 * the window (the item's own target). After an explosion and six frames of 0.05 s:
 *   - the explosion shows: pixels in the item's rectangle changed against the frame before it,
 *     also right around the rectangle above it;
 *   - the rectangle and its text are intact pixel for pixel, and so is everything outside the
 *     item;
 *   - the whole GL state (tests/gl/gl_snapshot.h) is the same right after the item's GL work as
 *     right before it, in every frame, and that work left no GL error. */
#include <QtCore/QDir>
#include <QtCore/QElapsedTimer>
#include <QtGui/QGuiApplication>
#include <QtGui/QImage>
#include <QtGui/QSurfaceFormat>
#include <QtQml/QQmlComponent>
#include <QtQml/QQmlEngine>
#include <QtQuick/QQuickWindow>

#include "check.h"
#include "gl_snapshot.h"
#include "sbfx_item.h"

enum { W = 480, H = 320 };

/* The overlay: an opaque bar with text over the middle of the item. */
struct Box {
    int x, y, width, height;
    bool contains(int px, int py) const { return px >= x && px < x + width && py >= y && py < y + height; }
};

static QString scene_qml(const Box &item, const Box &overlay)
{
    return QStringLiteral(R"(
import QtQuick
import Sbfx 1.0
Rectangle {
    width: %1; height: %2
    color: "#2a4d6e"
    Rectangle { y: %2 / 2; width: %1; height: %2 / 2; color: "#6e5a3a" }
    SbfxItem { objectName: "fx"; x: %3; y: %4; width: %5; height: %6; fixedStep: 0.05 }
    Rectangle {
        x: %7; y: %8; width: %9; height: %10; color: "#e8e8e8"
        Text { anchors.centerIn: parent; text: "QML on top"; color: "black"; font.pixelSize: 16 }
    }
}
)")
        .arg(W).arg(H).arg(item.x).arg(item.y).arg(item.width).arg(item.height)
        .arg(overlay.x).arg(overlay.y).arg(overlay.width).arg(overlay.height);
}

/* Checks of the item's GL work, made by its render observer in every frame. */
struct GlChecks {
    snapshot before, after;
    int frames = 0, state_changes = 0, errors = 0;
    char first_change[256] = "";
    GLenum first_error = GL_NO_ERROR;
    bool es = false;
    char version[128] = "";
};
static GlChecks checks;

static void observe(bool after)
{
    if (!after) {
        snprintf(checks.version, sizeof(checks.version), "%s", (const char *)glGetString(GL_VERSION));
        checks.es = strstr(checks.version, "OpenGL ES") != nullptr;
        if (!checks.es) { /* the compatibility profile's attribute 0 has no current value to query */
            GLint profile = 0;
            glGetIntegerv(0x9126 /* GL_CONTEXT_PROFILE_MASK */, &profile);
            snap_compat_profile = (profile & 0x2 /* COMPATIBILITY_PROFILE_BIT */) != 0;
        }
        while (glGetError() != GL_NO_ERROR) {} /* Qt's own (Qt 6.4: glPolygonMode on ES) */
        snapshot_take(&checks.before, false);
        GLenum e = glGetError();
        if (e != GL_NO_ERROR && checks.errors++ == 0) checks.first_error = e; /* the snapshot's own */
        return;
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR && checks.errors++ == 0) checks.first_error = e;
    snapshot_take(&checks.after, false);
    char first[256] = "";
    int diffs = snapshot_diff(&checks.before, &checks.after, "the item's render", first, sizeof(first));
    if (diffs > 0 && checks.state_changes++ == 0) snprintf(checks.first_change, sizeof(checks.first_change), "%s", first);
    checks.frames++;
}

/* Pixels that differ between two frames, inside `inside` and outside `outside`. */
static int changed(const QImage &a, const QImage &b, const Box &inside, const Box *outside)
{
    int n = 0;
    for (int y = inside.y; y < inside.y + inside.height; y++)
        for (int x = inside.x; x < inside.x + inside.width; x++)
            if (!(outside && outside->contains(x, y)) && a.pixel(x, y) != b.pixel(x, y)) n++;
    return n;
}

/* Qt as a user sets it up, the QML scene in a window, the item found and observed; returns
 * false (after a failed check) when something of that did not happen. */
struct Harness {
    QGuiApplication *app = nullptr;
    QQmlEngine *engine = nullptr;
    QQuickWindow *window = nullptr;
    QQuickItem *root = nullptr;
    SbfxItem *fx = nullptr;

    /* es: ask for OpenGL ES 3.0 as the example does; else Qt's default desktop context */
    bool open(const Box &item, const Box &overlay, bool es = true)
    {
        setenv("QT_QPA_PLATFORM", "xcb", 0); /* the VM tier runs it on eglfs (tests/vm/guest.sh) */
        if (strcmp(getenv("QT_QPA_PLATFORM"), "xcb") == 0 && !getenv("DISPLAY"))
            CHECK_SKIP("no X display: tests/hosts/qt_quick.sh runs this under xvfb-run");
        setenv("QSG_RENDER_LOOP", "basic", 1);
        QSurfaceFormat format;
        format.setRenderableType(QSurfaceFormat::OpenGLES);
        format.setVersion(3, 0);
        format.setDepthBufferSize(24);
        format.setStencilBufferSize(8);
        if (es) QSurfaceFormat::setDefaultFormat(format);
        QQuickWindow::setGraphicsApi(QSGRendererInterface::OpenGL);
        static int argc = 1;
        static char name[] = "test_qt_quick", *argv[] = {name, nullptr};
        app = new QGuiApplication(argc, argv);
        SbfxItem::registerQmlType();
        engine = new QQmlEngine;
        QQmlComponent component(engine);
        component.setData(scene_qml(item, overlay).toUtf8(), QUrl("qrc:/test.qml"));
        root = qobject_cast<QQuickItem *>(component.create());
        CHECK(root != nullptr, "%s", qPrintable(component.errorString()));
        if (!root) return false;
        window = new QQuickWindow;
        window->resize(W, H);
        root->setParentItem(window->contentItem());
        fx = root->findChild<SbfxItem *>("fx");
        fx->setRenderObserver(observe);
        window->show();
        QElapsedTimer waited;
        waited.start();
        while (!window->isExposed() && waited.elapsed() < 10000)
            QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
        CHECK(window->isExposed(), "the window was not exposed within 10 s");
        return window->isExposed();
    }
    /* One frame (the basic render loop renders one per grab) after the queued events. */
    QImage frame()
    {
        QCoreApplication::processEvents();
        return window->grabWindow().convertToFormat(QImage::Format_RGBA8888);
    }
    QImage frames(int n)
    {
        QImage last;
        for (int i = 0; i < n; i++) last = frame();
        return last;
    }
    ~Harness()
    {
        delete root;
        delete window;
        delete engine;
        delete app;
    }
};

static void check_gl_contract(bool es = true)
{
    printf("# GL state: %d frames observed, %d with a change (%s), %d with a GL error (first 0x%04x)\n",
           checks.frames, checks.state_changes, checks.first_change, checks.errors, checks.first_error);
    CHECK(checks.es == es, "Qt made %s OpenGL ES context", checks.es ? "an" : "no");
    CHECK(checks.frames >= 7, "the observer saw %d frames", checks.frames);
    CHECK(checks.state_changes == 0, "the GL state changed in %d frames: %s", checks.state_changes, checks.first_change);
    CHECK(checks.errors == 0, "GL error 0x%04x after the item's work in %d frames", checks.first_error, checks.errors);
}

/* The fire's lights for the host (sbfx_emitted_lights) as the item exposes them to QML. */
static void check_emitted_lights(const SbfxItem *fx, int changes)
{
    const QVariantList lights = fx->emittedLights();
    printf("# %lld emitted lights (%d changes)", (long long)lights.size(), changes);
    CHECK(!lights.isEmpty() && lights.size() <= SBFX_MAX_POINT_LIGHTS, "%lld lights from a burning explosion",
          (long long)lights.size());
    CHECK(changes > 0, "emittedLightsChanged was not emitted");
    CHECK(size_t(lights.size()) == fx->emittedPointLights().size(), "the QML and C++ lists differ");
    for (const QVariant &v : lights) {
        const QVariantMap l = v.toMap();
        const QVector3D position = l.value("position").value<QVector3D>(), color = l.value("color").value<QVector3D>();
        const double radius = l.value("radius").toDouble();
        printf(" (%.2f %.2f %.2f | %.3g %.3g %.3g | %.1f)", position.x(), position.y(), position.z(), color.x(),
               color.y(), color.z(), radius);
        CHECK(position.length() < 3.0f, "a light %.2f m from the explosion", position.length());
        CHECK(color.x() > 0.0f && color.x() >= color.y() && color.y() >= color.z(), "not fire's colour");
        CHECK(radius > 0.5, "radius %g", radius);
    }
    printf("\n");
}

static void run_case(const Box &item, bool expect_own_target, bool es = true)
{
    const Box overlay = {item.x + item.width / 2 - 60, item.y + item.height / 2 - 16, 120, 32};
    Harness h;
    if (!h.open(item, overlay, es)) return;
    const QImage before = h.frame();
    /* eglfs makes the window as large as the screen: the scene is in its top left W x H */
    CHECK(before.width() >= W && before.height() >= H, "grabbed %dx%d", before.width(), before.height());
    int lights_changed = 0;
    QObject::connect(h.fx, &SbfxItem::emittedLightsChanged, [&] { lights_changed++; });
    h.fx->trigger("explosion", QVector3D(0, 0, 0));
    const QImage after = h.frames(6);
    const SbfxNodeStatus s = h.fx->status();
    check_emitted_lights(h.fx, lights_changed);
    printf("# %s; item %dx%d at (%d, %d), %s; %d frames drawn, %d particles\n", checks.version, s.width, s.height, item.x, item.y,
           s.own_target ? "own target" : "Qt's framebuffer", s.frames, s.particles_alive);
    CHECK(h.fx->error().isEmpty() && s.error.isEmpty(), "%s", qPrintable(h.fx->error() + s.error));
    CHECK(s.own_target == expect_own_target, "own target: %d", s.own_target);
    CHECK(s.width == item.width && s.height == item.height, "the item drew at %dx%d", s.width, s.height);
    CHECK(s.frames >= 5 && s.particles_alive > 0, "%d frames drawn, %d particles", s.frames, s.particles_alive);

    int in_item = changed(before, after, item, &overlay);
    int item_pixels = item.width * item.height - overlay.width * overlay.height;
    const Box ring = {overlay.x - 16, overlay.y - 16, overlay.width + 32, overlay.height + 32};
    int around = changed(before, after, ring, &overlay);
    printf("# explosion: %d of %d pixels of the item changed, %d of %d around the rectangle above it\n", in_item,
           item_pixels, around, ring.width * ring.height - overlay.width * overlay.height);
    CHECK(in_item > item_pixels / 50, "the explosion changed only %d pixels", in_item);
    CHECK(around > (ring.width * ring.height - overlay.width * overlay.height) / 4,
          "the explosion is not under the rectangle: %d pixels around it changed", around);
    CHECK(changed(before, after, overlay, nullptr) == 0, "%d pixels of the QML rectangle above the item changed",
          changed(before, after, overlay, nullptr));
    const Box window_box = {0, 0, W, H};
    CHECK(changed(before, after, window_box, &item) == 0, "%d pixels outside the item changed",
          changed(before, after, window_box, &item));
    check_gl_contract(es);
}

CHECK_TEST(item_fills_the_window)
{
    run_case({0, 0, W, H}, false);
}

CHECK_TEST(item_smaller_than_the_window)
{
    run_case({60, 40, 300, 220}, true);
}

/* Without the ES request Qt makes a desktop OpenGL 4.5 context, on which sbfx runs too
 * (docs/hosts/desktop-gl.md): the smaller item, through its own target. */
CHECK_TEST(desktop_opengl_context)
{
    run_case({60, 40, 300, 220}, true, false);
}

/* The camera: a C++ hook looking away from the explosion hides it (and is given the item's size
 * in pixels); the view and projection properties looking at it show it again. */
CHECK_TEST(camera_hook_and_matrix_properties)
{
    const Box item = {0, 0, W, H}, nowhere = {-1, -1, 0, 0};
    Harness h;
    if (!h.open(item, nowhere)) return;
    int hook_width = 0, hook_height = 0;
    h.fx->setCameraHook([&](int width, int height, double, float view[16], float projection[16]) {
        hook_width = width;
        hook_height = height;
        const float eye[3] = {0, 2, 10}, away[3] = {0, 2, 20}, up[3] = {0, 1, 0};
        sbfx_look_at(view, eye, away, up);
        sbfx_perspective(projection, 0.87f, float(width) / float(height), 0.1f, 200.0f);
    });
    const QImage before = h.frame();
    h.fx->trigger("explosion", QVector3D(0, 0, 0));
    const QImage away = h.frames(6);
    CHECK(hook_width == W && hook_height == H, "the hook was given %dx%d", hook_width, hook_height);
    CHECK(h.fx->status().particles_alive > 0, "no particles");
    CHECK(changed(before, away, item, nullptr) == 0, "looking away, %d pixels changed", changed(before, away, item, nullptr));

    h.fx->setCameraHook(nullptr);
    QMatrix4x4 view, projection;
    view.lookAt(QVector3D(0, 2, 10), QVector3D(0, 1, 0), QVector3D(0, 1, 0));
    projection.perspective(50.0f, float(W) / float(H), 0.1f, 200.0f);
    h.fx->setViewMatrix(view);
    h.fx->setProjectionMatrix(projection);
    const QImage toward = h.frames(2);
    int seen = changed(before, toward, item, nullptr);
    printf("# looking away: 0 pixels changed; the properties looking at it: %d\n", seen);
    CHECK(seen > W * H / 100, "with the view and projection properties only %d pixels changed", seen);
    CHECK(h.fx->error().isEmpty(), "%s", qPrintable(h.fx->error()));
    check_gl_contract();
}

/* The scene, quality and budget properties: explosion.cfg fires its explosion from its timeline
 * (no trigger); a quality level switches without an error, a bad one is named in `error`, and so
 * are an effect the scene has not and a budget sbfx_create refuses, until a good one. */
CHECK_TEST(scene_quality_and_budget_properties)
{
    const Box item = {0, 0, W, H}, nowhere = {-1, -1, 0, 0};
    Harness h;
    if (!h.open(item, nowhere)) return;
    const QImage before = h.frame();
    h.fx->setScene(QUrl::fromLocalFile(QDir::current().absoluteFilePath("scenes/explosion.cfg")).toString());
    h.fx->setQuality("spherical/8/bl");
    const QImage after = h.frames(6);
    const SbfxNodeStatus s = h.fx->status();
    int seen = changed(before, after, item, nullptr);
    printf("# explosion.cfg's timeline: %d triggers, %d pixels changed\n", s.triggers_fired, seen);
    CHECK(h.fx->error().isEmpty(), "%s", qPrintable(h.fx->error()));
    CHECK(s.triggers_fired == 1, "%d triggers fired", s.triggers_fired);
    CHECK(seen > W * H / 100, "only %d pixels changed", seen);
    h.fx->setQuality("exact/3/nd");
    CHECK(h.fx->error().contains("exact/3/nd"), "a bad quality level gave the error \"%s\"", qPrintable(h.fx->error()));
    h.fx->trigger("no-such-effect", QVector3D(0, 0, 0));
    h.frames(3);
    QCoreApplication::processEvents();
    printf("# an unknown effect: %s\n", qPrintable(h.fx->error()));
    CHECK(h.fx->error().contains("no-such-effect"), "an unknown effect gave the error \"%s\"", qPrintable(h.fx->error()));
    h.fx->setBudget(-5.0);
    h.frames(3);
    QCoreApplication::processEvents();
    printf("# budget -5 ms: %s\n", qPrintable(h.fx->error()));
    CHECK(h.fx->error().contains("frame_budget_ms -5"), "budget -5 gave the error \"%s\"", qPrintable(h.fx->error()));
    h.fx->setBudget(8.0);
    h.frames(3);
    QCoreApplication::processEvents();
    CHECK(h.fx->error().isEmpty(), "with a budget of 8 ms: \"%s\"", qPrintable(h.fx->error()));
    check_gl_contract();
}

/* The scene property replaces the live module's scene (sbfx_set_scene, issue 29): each new file is
 * a reload of the same module (scene_reloads counts them), its timeline fires; a file that does
 * not load is named in `error` while the old scene plays on; reloadScene() reads the file again. */
CHECK_TEST(scene_property_reloads_the_live_module)
{
    const Box item = {0, 0, W, H}, nowhere = {-1, -1, 0, 0};
    Harness h;
    if (!h.open(item, nowhere)) return;
    h.frames(2); /* the module, with the built-in explosion */
    const QString dir = QDir::current().absoluteFilePath("scenes/");
    h.fx->setScene(QUrl::fromLocalFile(dir + "explosion.cfg").toString());
    h.frames(4);
    SbfxNodeStatus s = h.fx->status();
    CHECK(h.fx->error().isEmpty(), "%s", qPrintable(h.fx->error()));
    CHECK(s.scene_reloads == 1 && s.triggers_fired == 1, "explosion.cfg: %d reloads, %d triggers", s.scene_reloads,
          s.triggers_fired);
    h.fx->setScene(dir + "smoke.cfg");
    h.frames(4);
    s = h.fx->status();
    printf("# smoke.cfg into the live module: %d reloads, %d triggers, %d particles\n", s.scene_reloads,
           s.triggers_fired, s.particles_alive);
    CHECK(h.fx->error().isEmpty(), "%s", qPrintable(h.fx->error()));
    CHECK(s.scene_reloads == 2 && s.triggers_fired == 1 && s.particles_alive > 0,
          "smoke.cfg: %d reloads, %d triggers, %d particles", s.scene_reloads, s.triggers_fired, s.particles_alive);
    h.fx->setScene(dir + "no-such-scene.cfg");
    h.frames(3);
    QCoreApplication::processEvents();
    const SbfxNodeStatus kept = h.fx->status();
    printf("# a missing file: %s\n", qPrintable(h.fx->error()));
    CHECK(h.fx->error().contains("no-such-scene.cfg"), "a missing scene gave the error \"%s\"", qPrintable(h.fx->error()));
    CHECK(kept.scene_reloads == 2 && kept.particles_alive > 0 && kept.frames > s.frames,
          "the old scene stopped: %d reloads, %d particles", kept.scene_reloads, kept.particles_alive);
    h.fx->setScene(dir + "smoke.cfg");
    h.fx->reloadScene();
    h.frames(3);
    QCoreApplication::processEvents();
    CHECK(h.fx->error().isEmpty() && h.fx->status().scene_reloads == 3, "%s; %d reloads", qPrintable(h.fx->error()),
          h.fx->status().scene_reloads);
    check_gl_contract();
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
