// SPDX-License-Identifier: MIT
// A small freeglut viewer shared by the demos: orbit camera, flat-shaded meshes,
// a text overlay, and PNG capture of the frame (libpng, glReadPixels).
#pragma once

#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace sc::demo {

/// A triangle mesh to draw: positions (x, y, z triples) and index triples.
struct DrawMesh {
  std::vector<float> vertices;
  std::vector<int> indices;
};

/// One object of a frame: a mesh, its column-major 4x4 model matrix and colour.
struct DrawItem {
  const DrawMesh* mesh = nullptr;
  float matrix[16];
  float color[3];
};

/// An item that draws `mesh` with the column-major 4x4 `matrix` (any real type) in `color`.
template <class Real>
DrawItem drawItem(const DrawMesh* mesh, const Real* matrix, const float color[3]) {
  DrawItem item;
  item.mesh = mesh;
  for (int i = 0; i < 16; ++i) item.matrix[i] = float(matrix[i]);
  std::memcpy(item.color, color, sizeof(item.color));
  return item;
}

/// The overlay's text, printf-style, cut at 511 characters.
template <class... Args>
std::string overlayText(const char* format, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof(buf), format, args...);
  return buf;
}

struct ViewerCallbacks {
  std::function<void()> step;                           ///< advance the simulation (per frame)
  std::function<void(std::vector<DrawItem>&)> collect;  ///< the frame's objects
  std::function<std::string()> overlay;                 ///< text in the top-left corner
  std::function<void(unsigned char)> key;               ///< keys the viewer does not use
};

/// Opens a window (needs an X display) and runs the GLUT loop; never returns.
/// Keys: mouse drag orbits, wheel zooms, q / Esc quits.
void runViewer(int& argc, char** argv, const char* title, const ViewerCallbacks& callbacks,
               float target_y, float distance);

/// Opens a hidden-size window, draws one frame of `callbacks.collect` and writes it to
/// `png_path`. False (with a message on stderr) without a display or on write errors.
bool renderToPng(int& argc, char** argv, const ViewerCallbacks& callbacks, float target_y,
                 float distance, const std::string& png_path, int width = 800, int height = 600);

/// Writes RGB rows (bottom-up, as glReadPixels gives them) to a PNG file.
bool writePng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

}  // namespace sc::demo
