#include "sim/eda/layout/layout_png.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace shadesim {
namespace {

using Rgb = std::array<uint8_t, 3>;

// metal1 .. metal6, then anything else.
Rgb layer_colour(const std::string& layer) {
  static const std::array<Rgb, 7> colours = {{{70, 110, 255},
                                              {230, 60, 60},
                                              {60, 200, 90},
                                              {240, 200, 40},
                                              {60, 210, 220},
                                              {240, 240, 240},
                                              {200, 120, 220}}};
  if (layer.rfind("metal", 0) == 0 && layer.size() == 6 && layer[5] >= '1' && layer[5] <= '6')
    return colours[static_cast<size_t>(layer[5] - '1')];
  return colours[6];
}

struct Canvas {
  Image image;
  double x0, y0, scale;  // die origin (um) and pixels per um

  int px(double x_um) const { return static_cast<int>(std::floor((x_um - x0) * scale)); }
  int py(double y_um) const {
    return image.height - 1 - static_cast<int>(std::floor((y_um - y0) * scale));
  }
  void put(int x, int y, const Rgb& c) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    const size_t at = 3 * (static_cast<size_t>(y) * static_cast<size_t>(image.width) + x);
    std::copy(c.begin(), c.end(), image.pixels.begin() + static_cast<long>(at));
  }
  void fill(int xa, int ya, int xb, int yb, const Rgb& c) {
    for (int y = std::min(ya, yb); y <= std::max(ya, yb); ++y)
      for (int x = std::min(xa, xb); x <= std::max(xa, xb); ++x) put(x, y, c);
  }
};

}  // namespace

Image draw_layout(const DefSummary& def, const std::map<std::string, LefSize>& sizes,
                  int max_side) {
  const double w = def.die_x1_um - def.die_x0_um, h = def.die_y1_um - def.die_y0_um;
  if (w <= 0 || h <= 0 || max_side < 16)
    throw std::invalid_argument("draw_layout: an empty die or a picture under 16 pixels");
  const double scale = max_side / std::max(w, h);
  Canvas c{Image(std::max(1, static_cast<int>(std::ceil(w * scale))),
                 std::max(1, static_cast<int>(std::ceil(h * scale))), 3),
           def.die_x0_um, def.die_y0_um, scale};
  c.fill(0, 0, c.image.width - 1, c.image.height - 1, {18, 18, 24});
  for (const DefComponent& p : def.placed) {
    const auto s = sizes.find(p.cell);
    if (s == sizes.end()) continue;
    const bool fill = p.cell == "FILL";
    const Rgb body = fill ? Rgb{45, 45, 52} : Rgb{105, 105, 115};
    c.fill(c.px(p.x_um), c.py(p.y_um), c.px(p.x_um + s->second.width_um) - 1,
           c.py(p.y_um + s->second.height_um) + 1, body);
  }
  // Lower layers first, so the upper ones show where they cross.
  std::vector<const DefSegment*> order;
  for (const DefSegment& s : def.segments) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(),
                   [](const DefSegment* a, const DefSegment* b) { return a->layer < b->layer; });
  for (const DefSegment* s : order) {
    const Rgb col = layer_colour(s->layer);
    const int xa = c.px(s->x0_um), ya = c.py(s->y0_um), xb = c.px(s->x1_um), yb = c.py(s->y1_um);
    const int n = std::max(std::abs(xb - xa), std::abs(yb - ya));
    for (int k = 0; k <= n; ++k) {
      const double f = n ? static_cast<double>(k) / n : 0;
      c.put(static_cast<int>(std::lround(xa + f * (xb - xa))),
            static_cast<int>(std::lround(ya + f * (yb - ya))), col);
    }
  }
  const Rgb edge{200, 200, 200};
  c.fill(0, 0, c.image.width - 1, 0, edge);
  c.fill(0, c.image.height - 1, c.image.width - 1, c.image.height - 1, edge);
  c.fill(0, 0, 0, c.image.height - 1, edge);
  c.fill(c.image.width - 1, 0, c.image.width - 1, c.image.height - 1, edge);
  return c.image;
}

}  // namespace shadesim
