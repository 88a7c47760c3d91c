/* sbfx-qt-quick: sbfx between Qt Quick items (main.qml, docs/hosts/qt-quick.md). Space, the
 * button or a timer starts an explosion.
 *   sbfx-qt-quick [--scene FILE] [--effect NAME] [--every MS] [--frames N]
 * --every MS: the timer's period (2000, 0: none); --frames N: quits after N frames (0: when the
 * window closes). Headless: QT_QPA_PLATFORM=xcb under Xvfb (xvfb-run). */
#include <QtCore/QUrl>
#include <QtGui/QGuiApplication>
#include <QtGui/QSurfaceFormat>
#include <QtQml/QQmlContext>
#include <QtQuick/QQuickView>
#include <cstdio>

#include "sbfx_item.h"

int main(int argc, char **argv)
{
    /* sbfx needs OpenGL ES 3.0 and Qt Quick on OpenGL: both before QGuiApplication exists */
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGLES);
    format.setVersion(3, 0);
    format.setDepthBufferSize(24);
    format.setStencilBufferSize(8);
    QSurfaceFormat::setDefaultFormat(format);
    QQuickWindow::setGraphicsApi(QSGRendererInterface::OpenGL);
    QGuiApplication app(argc, argv);
    SbfxItem::registerQmlType();

    QString scene, effect = QStringLiteral("explosion");
    int every_ms = 2000, frames = 0;
    const QStringList args = app.arguments();
    for (int i = 1; i < args.size(); i++) {
        const bool has_value = i + 1 < args.size();
        if (args[i] == "--scene" && has_value) scene = args[++i];
        else if (args[i] == "--effect" && has_value) effect = args[++i];
        else if (args[i] == "--every" && has_value) every_ms = args[++i].toInt();
        else if (args[i] == "--frames" && has_value) frames = args[++i].toInt();
        else {
            std::fprintf(stderr, "usage: %s [--scene FILE] [--effect NAME] [--every MS] [--frames N]\n", argv[0]);
            return 2;
        }
    }

    QQuickView view;
    view.rootContext()->setContextProperty("sceneFile", scene);
    view.rootContext()->setContextProperty("effectName", effect);
    view.rootContext()->setContextProperty("triggerEvery", every_ms);
    view.setResizeMode(QQuickView::SizeRootObjectToView);
    view.setTitle("sbfx in Qt Quick (space: explosion)");
    view.setSource(QUrl("qrc:/main.qml"));
    if (view.status() != QQuickView::Ready) return 1; /* Qt printed the QML errors */
    auto *fx = view.rootObject()->findChild<SbfxItem *>("fx");

    int swapped = 0;
    if (frames > 0)
        QObject::connect(&view, &QQuickWindow::frameSwapped, &app, [&] {
            if (++swapped == frames) app.quit();
        });
    view.show();
    int rc = app.exec();
    std::printf("sbfx-qt-quick: %d explosions\n", fx->triggers());
    if (!fx->error().isEmpty()) {
        std::fprintf(stderr, "sbfx-qt-quick: %s\n", qPrintable(fx->error()));
        rc = 1;
    }
    return rc;
}
