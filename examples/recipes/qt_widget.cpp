// SPDX-License-Identifier: MIT
// qt_widget.cpp — glass in a Qt QOpenGLWidget on GLES 3.0 (QSurfaceFormat's
// renderable type OpenGLES, set before the QApplication is made). Qt draws
// the widget into its own framebuffer object: snell draws into it in
// paintGL, where Qt has bound it and made the context current.
//   c++ -fPIC qt_widget.cpp $(pkg-config --cflags --libs Qt5Widgets snell)
#include <QApplication>
#include <QOpenGLWidget>
#include <QSurfaceFormat>
#include <cstdio>

extern "C" {
#include "glass.h"
}

class GlassWidget : public QOpenGLWidget
{
  public:
    ~GlassWidget() override
    {
        makeCurrent(); // snell's GL objects go in the widget's context
        if (open_) glass_close(&glass_);
        doneCurrent();
    }

  protected:
    void resizeGL(int, int) override
    {
        // the framebuffer in pixels (the widget's size times the device pixel ratio)
        const int w = int(width() * devicePixelRatioF()), h = int(height() * devicePixelRatioF());
        if (open_) glass_close(&glass_);
        open_ = glass_open(&glass_, w, h);
    }
    void paintGL() override
    {
        snell_camera cam = {}; // stands in for the app's own view and projection
        float eye[3], view[16], proj[16];
        snell_camera_matrices(&cam, float(width()) / float(height()), eye, view, proj);
        // ... the app's scene, drawn into the bound framebuffer (defaultFramebufferObject()) ...
        if (open_ && glass_draw(&glass_, view, proj) != SNELL_OK)
            std::fprintf(stderr, "glass: %s\n", snell_last_error(glass_.ctx));
    }

  private:
    glass_app glass_{};
    bool open_ = false;
};

int main(int argc, char **argv)
{
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGLES);
    format.setVersion(3, 0);
    format.setDepthBufferSize(24); // snell depth-tests the glass
    QSurfaceFormat::setDefaultFormat(format);
    QApplication app(argc, argv);
    GlassWidget w;
    w.resize(640, 480);
    w.show();
    return app.exec();
}
