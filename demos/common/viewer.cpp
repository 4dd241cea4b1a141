// SPDX-License-Identifier: MIT
// freeglut viewer: fixed-function lighting with per-face normals (flat shading),
// an orbit camera, and PNG capture through libpng.
#include "viewer.h"

#include <GL/freeglut.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sc::demo {

namespace {

struct State {
  ViewerCallbacks callbacks;
  float yaw = 0.6f, pitch = 0.35f, distance = 12.0f, target_y = 2.0f;
  int last_x = 0, last_y = 0;
  bool dragging = false;
  int width = 1024, height = 768;
};
State g_state;

void setCamera(int width, int height) {
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  gluPerspective(45.0, double(width) / double(height > 0 ? height : 1), 0.05, 500.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const float cp = std::cos(g_state.pitch), sp = std::sin(g_state.pitch);
  const float ex = g_state.distance * cp * std::sin(g_state.yaw);
  const float ey = g_state.target_y + g_state.distance * sp;
  const float ez = g_state.distance * cp * std::cos(g_state.yaw);
  gluLookAt(ex, ey, ez, 0, g_state.target_y, 0, 0, 1, 0);
}

void drawMesh(const DrawMesh& m) {
  glBegin(GL_TRIANGLES);
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const float* a = &m.vertices[3 * static_cast<std::size_t>(m.indices[t])];
    const float* b = &m.vertices[3 * static_cast<std::size_t>(m.indices[t + 1])];
    const float* c = &m.vertices[3 * static_cast<std::size_t>(m.indices[t + 2])];
    const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0f) {
      for (float& x : n) x /= len;
    }
    glNormal3fv(n);
    glVertex3fv(a);
    glVertex3fv(b);
    glVertex3fv(c);
  }
  glEnd();
}

void drawScene(int width, int height) {
  glClearColor(0.93f, 0.94f, 0.96f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_COLOR_MATERIAL);
  glEnable(GL_NORMALIZE);
  glShadeModel(GL_FLAT);
  setCamera(width, height);
  const float light[4] = {0.4f, 1.0f, 0.6f, 0.0f};
  glLightfv(GL_LIGHT0, GL_POSITION, light);
  std::vector<DrawItem> items;
  if (g_state.callbacks.collect) g_state.callbacks.collect(items);
  for (const DrawItem& item : items) {
    glPushMatrix();
    glMultMatrixf(item.matrix);
    glColor3fv(item.color);
    drawMesh(*item.mesh);
    glPopMatrix();
  }
  if (g_state.callbacks.overlay) {
    glDisable(GL_LIGHTING);
    glDisable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    gluOrtho2D(0, width, 0, height);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glColor3f(0.1f, 0.1f, 0.1f);
    int y = height - 20;
    const std::string text = g_state.callbacks.overlay();
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t end = text.find('\n', start);
      const std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
      glRasterPos2i(10, y);
      for (char ch : line) glutBitmapCharacter(GLUT_BITMAP_9_BY_15, ch);
      y -= 18;
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
}

void onDisplay() {
  drawScene(g_state.width, g_state.height);
  glutSwapBuffers();
}

void onIdle() {
  if (g_state.callbacks.step) g_state.callbacks.step();
  glutPostRedisplay();
}

void onReshape(int w, int h) {
  g_state.width = w;
  g_state.height = h;
}

void onMouse(int button, int state, int x, int y) {
  if (button == GLUT_LEFT_BUTTON) {
    g_state.dragging = state == GLUT_DOWN;
    g_state.last_x = x;
    g_state.last_y = y;
  } else if (state == GLUT_DOWN && (button == 3 || button == 4)) {
    g_state.distance *= button == 3 ? 0.9f : 1.1f;  // wheel
  }
}

void onMotion(int x, int y) {
  if (!g_state.dragging) return;
  g_state.yaw -= 0.01f * float(x - g_state.last_x);
  g_state.pitch = std::fmax(-1.5f, std::fmin(1.5f, g_state.pitch + 0.01f * float(y - g_state.last_y)));
  g_state.last_x = x;
  g_state.last_y = y;
}

void onKey(unsigned char key, int, int) {
  if (key == 27 || key == 'q') std::exit(0);
  if (g_state.callbacks.key) g_state.callbacks.key(key);
}

bool initGlut(int& argc, char** argv, const char* title, int width, int height) {
  // freeglut exits on a missing display; check first so headless callers can go on.
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || display[0] == '\0') {
    std::fprintf(stderr, "no X display (DISPLAY unset): run under xvfb-run -a\n");
    return false;
  }
  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_RGB | GLUT_DOUBLE | GLUT_DEPTH);
  glutInitWindowSize(width, height);
  glutCreateWindow(title);
  return true;
}

}  // namespace

void runViewer(int& argc, char** argv, const char* title, const ViewerCallbacks& callbacks,
               float target_y, float distance) {
  g_state.callbacks = callbacks;
  g_state.target_y = target_y;
  g_state.distance = distance;
  if (!initGlut(argc, argv, title, g_state.width, g_state.height)) std::exit(1);
  glutDisplayFunc(onDisplay);
  glutIdleFunc(onIdle);
  glutReshapeFunc(onReshape);
  glutMouseFunc(onMouse);
  glutMotionFunc(onMotion);
  glutKeyboardFunc(onKey);
  glutMainLoop();
}

bool renderToPng(int& argc, char** argv, const ViewerCallbacks& callbacks, float target_y,
                 float distance, const std::string& png_path, int width, int height) {
  g_state.callbacks = callbacks;
  g_state.target_y = target_y;
  g_state.distance = distance;
  if (!initGlut(argc, argv, "smartcollision", width, height)) return false;
  drawScene(width, height);
  glFinish();
  std::vector<unsigned char> rgb(static_cast<std::size_t>(3 * width * height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  return writePng(png_path, width, height, rgb);
}

bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return false;
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return false;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int row = height - 1; row >= 0; --row)  // glReadPixels rows are bottom-up
    png_write_row(png, &rgb[static_cast<std::size_t>(3 * width * row)]);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
  return true;
}

}  // namespace sc::demo
