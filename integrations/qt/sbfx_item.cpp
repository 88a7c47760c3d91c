/* SbfxItem: sbfx_item.h. Runs on Qt's GUI thread but for updatePaintNode, which Qt calls on the
 * render thread while the GUI thread waits: the only place the item and its node meet. */
#include "sbfx_item.h"

#include <QtCore/QUrl>
#include <QtCore/QVariantMap>
#include <cstring>
#include <QtQml/QQmlEngine>
#include <QtQuick/QQuickWindow>
#include <QtQuick/QSGRendererInterface>

SbfxItem::SbfxItem(QQuickItem *parent) : QQuickItem(parent) { setFlag(ItemHasContents, true); }

void SbfxItem::registerQmlType() { qmlRegisterType<SbfxItem>("Sbfx", 1, 0, "SbfxItem"); }

void SbfxItem::trigger(const QString &effect, const QVector3D &position)
{
    triggers_.push_back({effect.toUtf8(), {position.x(), position.y(), position.z()}});
    update();
}

void SbfxItem::setCameraHook(CameraHook hook)
{
    settings_.camera_hook = std::move(hook);
    settings_changed();
}

void SbfxItem::setRenderObserver(RenderObserver observer)
{
    settings_.render_observer = std::move(observer);
    settings_changed();
}

void SbfxItem::setScene(const QString &scene)
{
    const QUrl url(scene);
    const QString path = url.isLocalFile() ? url.toLocalFile() : scene;
    if (path == settings_.scene_path) return;
    settings_.scene_path = path;
    settings_.scene_generation++;
    emit sceneChanged();
    settings_changed();
}

void SbfxItem::reloadScene()
{
    settings_.scene_generation++;
    settings_changed();
}

void SbfxItem::setQuality(const QString &quality)
{
    if (quality == quality_) return;
    quality_ = quality;
    char err[256] = "";
    settings_.has_quality = !quality.isEmpty();
    if (settings_.has_quality &&
        sbfx_quality_parse(quality.toUtf8().constData(), &settings_.quality, err, sizeof(err)) != SBFX_OK) {
        settings_.has_quality = false;
        setError(QStringLiteral("quality \"%1\": %2").arg(quality, QString::fromUtf8(err)));
    }
    settings_.quality_generation++;
    emit qualityChanged();
    settings_changed();
}

void SbfxItem::setBudget(double ms)
{
    if (ms == settings_.budget_ms) return;
    settings_.budget_ms = ms;
    settings_.module_generation++;
    emit budgetChanged();
    settings_changed();
}

void SbfxItem::setViewMatrix(const QMatrix4x4 &view)
{
    view_ = view;
    settings_.has_view = true;
    std::copy(view.constData(), view.constData() + 16, settings_.view);
    emit viewMatrixChanged();
    settings_changed();
}

void SbfxItem::setProjectionMatrix(const QMatrix4x4 &projection)
{
    projection_ = projection;
    settings_.has_projection = true;
    std::copy(projection.constData(), projection.constData() + 16, settings_.projection);
    emit projectionMatrixChanged();
    settings_changed();
}

void SbfxItem::setFixedStep(double seconds)
{
    if (seconds == settings_.fixed_step) return;
    settings_.fixed_step = seconds;
    emit fixedStepChanged();
    settings_changed();
}

void SbfxItem::setRunning(bool running)
{
    if (running == settings_.running) return;
    settings_.running = running;
    emit runningChanged();
    settings_changed();
}

/* The node copies the settings at the next sync only when they changed. */
void SbfxItem::settings_changed()
{
    settings_.generation++;
    update();
}

void SbfxItem::setError(const QString &error)
{
    if (error == error_) return;
    error_ = error;
    emit errorChanged();
}

static bool same_lights(const std::vector<sbfx_point_light> &a, const std::vector<sbfx_point_light> &b)
{
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

QVariantList SbfxItem::emittedLights() const
{
    QVariantList list;
    for (const sbfx_point_light &l : status_.emitted_lights)
        list.append(QVariantMap{{QStringLiteral("position"), QVector3D(l.position[0], l.position[1], l.position[2])},
                                {QStringLiteral("color"), QVector3D(l.color[0], l.color[1], l.color[2])},
                                {QStringLiteral("radius"), double(l.radius)}});
    return list;
}

/* Hands the node this frame's settings and triggers, takes its report of the last frame; the
 * signals and the next frame's request go to the GUI thread. */
QSGNode *SbfxItem::updatePaintNode(QSGNode *old, UpdatePaintNodeData *)
{
    const QSGRendererInterface::GraphicsApi api = window()->rendererInterface()->graphicsApi();
    if (api != QSGRendererInterface::OpenGL) {
        delete old;
        QMetaObject::invokeMethod(
            this,
            [this, api] {
                const QString name = api == QSGRendererInterface::Software
                                         ? QStringLiteral("its software renderer")
                                         : QStringLiteral("graphics API %1 (QSGRendererInterface)").arg(int(api));
                setError(QStringLiteral("Qt Quick draws with %1, not OpenGL: call "
                                        "QQuickWindow::setGraphicsApi(QSGRendererInterface::OpenGL) before "
                                        "QGuiApplication, on a platform with OpenGL (not QT_QPA_PLATFORM=offscreen)")
                             .arg(name));
            },
            Qt::QueuedConnection);
        return nullptr;
    }
    auto *node = static_cast<SbfxRenderNode *>(old);
    if (!node) node = new SbfxRenderNode;
    node->sync(settings_, triggers_, size());
    const SbfxNodeStatus report = node->status();
    const bool more_triggers = report.triggers_fired != status_.triggers_fired;
    const bool new_error = report.error != status_.error; /* also cleared: a new scene loaded */
    const bool lights_changed = !same_lights(report.emitted_lights, status_.emitted_lights);
    status_ = report;
    QMetaObject::invokeMethod(
        this,
        [this, more_triggers, new_error, lights_changed, error = report.error] {
            if (new_error) setError(error);
            if (more_triggers) emit triggersChanged();
            if (lights_changed) emit emittedLightsChanged();
            if (settings_.running) update();
        },
        Qt::QueuedConnection);
    return node;
}
