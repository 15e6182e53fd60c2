// Bird's-eye view of a point cloud, with range rings, a scale bar and a colour legend drawn in a
// built-in 5x7 bitmap font (digits, '-', '.', 'm').
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "hesai_port/formats/writers.h"

namespace hesai {
namespace port {
namespace {

// ---- the font: 7 rows of 5 pixels, bit 4 is the leftmost column ----

struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};

constexpr std::array<Glyph, 14> kFont = {{
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x15, 0x15}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {' ', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}},
}};
constexpr int kGlyphW = 5;
constexpr int kGlyphH = 7;
constexpr int kAdvance = 6;  // glyph width plus one column of spacing

const Glyph* find_glyph(char c) {
  for (const Glyph& g : kFont) {
    if (g.c == c) return &g;
  }
  return nullptr;
}

constexpr std::uint8_t kTextColor[3] = {225, 225, 225};
constexpr std::uint8_t kRingColor[3] = {38, 44, 58};
constexpr std::uint8_t kPanelColor[3] = {6, 7, 10};

class Canvas {
 public:
  explicit Canvas(RgbImage& img) : img_(img) {}

  void pixel(long x, long y, const std::uint8_t c[3]) {
    if (x < 0 || y < 0 || x >= static_cast<long>(img_.width) || y >= static_cast<long>(img_.height)) return;
    std::memcpy(img_.at(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)), c, 3);
  }
  void rect(long x0, long y0, long w, long h, const std::uint8_t c[3]) {
    for (long y = y0; y < y0 + h; ++y) {
      for (long x = x0; x < x0 + w; ++x) pixel(x, y, c);
    }
  }
  // Text with its top-left corner at (x, y), each font pixel drawn as s x s.
  void text(long x, long y, const char* s, long scale, const std::uint8_t c[3]) {
    for (; *s != '\0'; ++s, x += kAdvance * scale) {
      const Glyph* g = find_glyph(*s);
      if (g == nullptr) continue;
      for (int row = 0; row < kGlyphH; ++row) {
        for (int col = 0; col < kGlyphW; ++col) {
          const unsigned bits = g->rows[static_cast<std::size_t>(row)];
          if (((bits >> (kGlyphW - 1 - col)) & 1u) != 0) {
            rect(x + col * scale, y + row * scale, scale, scale, c);
          }
        }
      }
    }
  }

 private:
  RgbImage& img_;
};

long text_width(const char* s, long scale) {
  const auto n = static_cast<long>(std::strlen(s));
  return n == 0 ? 0 : (n * kAdvance - 1) * scale;
}

// Largest 1, 2 or 5 x 10^k not above `target` (target > 0).
double nice_step(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= target) return m * p;
  }
  return p;
}

// A legend or scale label: integers without decimals, others with one; `unit` appended.
void format_label(char* out, std::size_t size, double v, const char* unit) {
  const double r = std::round(v);
  const bool integral = std::fabs(v - r) < 1e-6;
  if (integral && r == 0.0) v = 0.0;  // no "-0"
  const std::to_chars_result res =
      std::to_chars(out, out + size - 8, integral ? r : v, std::chars_format::fixed, integral ? 0 : 1);
  char* end = res.ec == std::errc() ? res.ptr : out;
  const std::size_t n = std::strlen(unit);
  std::memcpy(end, unit, n);
  end[n] = '\0';
}

}  // namespace

void color_ramp(float t, std::uint8_t rgb[3]) {
  struct Stop {
    float t;
    float r, g, b;
  };
  static constexpr std::array<Stop, 5> kStops = {{{0.00f, 40, 70, 230},
                                                  {0.25f, 0, 190, 230},
                                                  {0.50f, 60, 210, 70},
                                                  {0.75f, 250, 220, 30},
                                                  {1.00f, 240, 40, 30}}};
  if (!(t > 0.0f)) t = 0.0f;  // also NaN
  if (t > 1.0f) t = 1.0f;
  std::size_t i = 0;
  while (i + 2 < kStops.size() && t > kStops[i + 1].t) ++i;
  const Stop& a = kStops[i];
  const Stop& b = kStops[i + 1];
  const float u = (t - a.t) / (b.t - a.t);
  rgb[0] = static_cast<std::uint8_t>(std::lround(a.r + (b.r - a.r) * u));
  rgb[1] = static_cast<std::uint8_t>(std::lround(a.g + (b.g - a.g) * u));
  rgb[2] = static_cast<std::uint8_t>(std::lround(a.b + (b.b - a.b) * u));
}

bool BirdseyeView::reset(const PngOptions& o, std::string* error) {
  value_.clear();
  auto fail = [&](const char* why) {
    if (error != nullptr) *error = std::string("invalid PNG options: ") + why;
    return false;
  };
  if (o.width < 64 || o.width > 16384 || o.height < 64 || o.height > 16384) {
    return fail("width and height must be 64..16384 pixels");
  }
  if (!std::isfinite(o.range_m) || !(o.range_m > 0.0f)) return fail("range_m must be a positive number");
  if (o.point_radius_px > 16) return fail("point_radius_px must be 0..16");
  const bool by_height = o.color_by == ColorBy::height;
  lo_ = by_height ? -3.0 : 0.0;
  hi_ = by_height ? 3.0 : 255.0;
  if (!std::isnan(o.color_min) || !std::isnan(o.color_max)) {
    if (!std::isfinite(o.color_min) || !std::isfinite(o.color_max) || !(o.color_min < o.color_max)) {
      return fail("color_min and color_max must both be set, finite, and min < max");
    }
    lo_ = o.color_min;
    hi_ = o.color_max;
  }
  if (error != nullptr) error->clear();
  options_ = o;
  const double w = o.width, h = o.height;
  ppm_ = (w < h ? w : h) / (2.0 * o.range_m);
  cx_ = w / 2.0;
  cy_ = h / 2.0;
  // Largest colour value per pixel (-inf: no point).
  value_.assign(static_cast<std::size_t>(o.width) * o.height, -std::numeric_limits<float>::infinity());
  return true;
}

void BirdseyeView::add(const Point* points, std::size_t count) {
  if (value_.empty()) return;
  const PngOptions& o = options_;
  const bool by_height = o.color_by == ColorBy::height;
  const auto w = static_cast<long>(o.width);  // <= 16384 (checked by reset): fits a 32-bit long
  const auto h = static_cast<long>(o.height);
  const double ppm = ppm_, cx = cx_, cy = cy_;
  const auto r = static_cast<long>(o.point_radius_px);
  for (std::size_t i = 0; i < count; ++i) {
    const Point& p = points[i];
    const float v = by_height ? p.z : static_cast<float>(p.intensity);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(v)) continue;
    const double fx = std::floor(cx + p.x * ppm);
    const double fy = std::floor(cy - p.y * ppm);
    if (fx < static_cast<double>(-r) || fy < static_cast<double>(-r) || fx >= static_cast<double>(w + r) ||
        fy >= static_cast<double>(h + r)) {
      continue;
    }
    const auto px = static_cast<long>(fx);
    const auto py = static_cast<long>(fy);
    for (long y = py - r; y <= py + r; ++y) {
      if (y < 0 || y >= h) continue;
      for (long x = px - r; x <= px + r; ++x) {
        if (x < 0 || x >= w) continue;
        float& cell = value_[static_cast<std::size_t>(y * w + x)];
        if (v > cell) cell = v;
      }
    }
  }
}

void BirdseyeView::clear() {
  std::fill(value_.begin(), value_.end(), -std::numeric_limits<float>::infinity());
}

RgbImage BirdseyeView::render() const {
  if (value_.empty()) return RgbImage();
  const PngOptions& o = options_;
  const bool by_height = o.color_by == ColorBy::height;
  const double lo = lo_;
  const double hi = hi_;
  const auto w = static_cast<long>(o.width);
  const auto h = static_cast<long>(o.height);
  const double ppm = ppm_, cx = cx_, cy = cy_;
  const long s = (w < h ? w : h) >= 1024 ? 2 : 1;  // scale of text and decorations
  const double step_m = nice_step(o.range_m / 3.0);
  const float kEmpty = -std::numeric_limits<float>::infinity();
  const std::vector<float>& value = value_;

  RgbImage img(o.width, o.height, kBackground[0], kBackground[1], kBackground[2]);
  Canvas canvas(img);

  // Range rings: pixels within half a pixel of a multiple of the step.
  if (o.range_rings) {
    const double step_px = step_m * ppm;
    for (long y = 0; y < h; ++y) {
      for (long x = 0; x < w; ++x) {
        const double dx = static_cast<double>(x) + 0.5 - cx;
        const double dy = static_cast<double>(y) + 0.5 - cy;
        const double d = std::sqrt(dx * dx + dy * dy) / step_px;
        const double k = std::round(d);
        if (k >= 1.0 && std::fabs(d - k) * step_px < 0.5) canvas.pixel(x, y, kRingColor);
      }
    }
  }

  // The points.
  const double span = hi - lo;
  for (long y = 0; y < h; ++y) {
    for (long x = 0; x < w; ++x) {
      const float v = value[static_cast<std::size_t>(y * w + x)];
      if (v == kEmpty) continue;
      std::uint8_t c[3];
      color_ramp(static_cast<float>((static_cast<double>(v) - lo) / span), c);
      canvas.pixel(x, y, c);
    }
  }

  // The sensor: a small white cross at the origin.
  {
    const auto ox = static_cast<long>(std::floor(cx));
    const auto oy = static_cast<long>(std::floor(cy));
    for (long d = -3 * s; d <= 3 * s; ++d) {
      canvas.pixel(ox + d, oy, kTextColor);
      canvas.pixel(ox, oy + d, kTextColor);
    }
  }

  const long margin = 12 * s;
  const long glyph_h = kGlyphH * s;

  // Scale bar, bottom left: a bar of step_m metres with ticks at 0, half and full length and
  // the length above its middle.
  if (o.scale_bar) {
    const auto len = static_cast<long>(std::lround(step_m * ppm));
    char label[32];
    format_label(label, sizeof label, step_m, "m");
    const long tick = 5 * s;
    const long panel_w = len + 2 * margin;
    const long panel_h = glyph_h + tick + 2 * s + 3 * s + 2 * margin;
    const long px0 = margin / 2;
    const long py0 = h - margin / 2 - panel_h;
    canvas.rect(px0, py0, panel_w, panel_h, kPanelColor);
    const long bx = px0 + margin;
    const long by = py0 + panel_h - margin - 2 * s;  // top of the bar
    canvas.rect(bx, by, len + s, 2 * s, kTextColor);
    for (long t : {0L, len / 2, len}) canvas.rect(bx + t, by - tick, s, tick, kTextColor);
    canvas.text(bx + len / 2 - text_width(label, s) / 2, by - tick - 3 * s - glyph_h, label, s, kTextColor);
  }

  // Colour legend, right: a vertical ramp (top = max) with its end and middle values.
  if (o.legend) {
    const long bar_w = 10 * s;
    const long bar_h = h * 2 / 5;
    const char* unit = by_height ? "m" : "";
    char top[32];
    char mid[32];
    char bottom[32];
    format_label(top, sizeof top, hi, unit);
    format_label(mid, sizeof mid, (lo + hi) / 2.0, unit);
    format_label(bottom, sizeof bottom, lo, unit);
    long label_w = text_width(top, s);
    if (text_width(mid, s) > label_w) label_w = text_width(mid, s);
    if (text_width(bottom, s) > label_w) label_w = text_width(bottom, s);
    const long panel_w = bar_w + label_w + 4 * s + 2 * margin;
    const long panel_h = bar_h + glyph_h + 2 * margin;
    const long px0 = w - margin / 2 - panel_w;
    const long py0 = margin / 2;
    canvas.rect(px0, py0, panel_w, panel_h, kPanelColor);
    const long bx = px0 + panel_w - margin - bar_w;
    const long by = py0 + margin + glyph_h / 2;
    for (long y = 0; y < bar_h; ++y) {
      std::uint8_t c[3];
      color_ramp(1.0f - static_cast<float>(y) / static_cast<float>(bar_h - 1), c);
      canvas.rect(bx, by + y, bar_w, 1, c);
    }
    const long lx = bx - 4 * s;
    canvas.text(lx - text_width(top, s), by - glyph_h / 2, top, s, kTextColor);
    canvas.text(lx - text_width(mid, s), by + bar_h / 2 - glyph_h / 2, mid, s, kTextColor);
    canvas.text(lx - text_width(bottom, s), by + bar_h - 1 - glyph_h / 2, bottom, s, kTextColor);
  }
  return img;
}

RgbImage render_birdseye(const Point* points, std::size_t count, const PngOptions& options, std::string* error) {
  BirdseyeView view;
  if (!view.reset(options, error)) return RgbImage();
  view.add(points, count);
  return view.render();
}

WriteResult write_png(const std::string& path, const BirdseyeView& view) {
  const RgbImage img = view.render();
  if (img.rgb.empty()) return WriteResult::failure("cannot write '" + path + "': no valid PNG options");
  const std::vector<std::uint8_t> png = encode_png(img, view.options().deflate);
  if (png.empty()) return WriteResult::failure("cannot write '" + path + "': PNG encoding failed");
  return write_file(path, png.data(), png.size());
}

WriteResult write_png(const std::string& path, const Point* points, std::size_t count, const PngOptions& options) {
  BirdseyeView view;
  std::string why;
  if (!view.reset(options, &why)) return WriteResult::failure("cannot write '" + path + "': " + why);
  view.add(points, count);
  return write_png(path, view);
}

WriteResult write_png(const std::string& path, const std::vector<Point>& points, const PngOptions& options) {
  return write_png(path, points.data(), points.size(), options);
}

}  // namespace port
}  // namespace hesai
