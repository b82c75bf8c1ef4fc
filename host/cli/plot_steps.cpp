// collide-plot: a PNG of per-step series from `collide run --out` CSV files (the demo's
// picture). Two panels sharing the step axis: a log-scale time panel and a linear count
// panel. Text uses a built-in 3x5 pixel font (upper case, digits, a few signs).
//
//   collide-plot OUT.png "TITLE" SERIES...
//   SERIES = time|count:LABEL=FILE:COLUMN     e.g. time:ODE CPU=ode.csv:ode_ns
//
// Rows whose value is <= 0 are left out of the log panel.
#include <png.h>

#include "cli/output_file.hpp"
#include "util/input_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Rgb { std::uint8_t r, g, b; };

class Image {
 public:
  Image(int w, int h) : w_(w), h_(h), px_(static_cast<std::size_t>(w) * h, Rgb{255, 255, 255}) {}
  void set(int x, int y, Rgb c) {
    if (x >= 0 && y >= 0 && x < w_ && y < h_) px_[static_cast<std::size_t>(y) * w_ + x] = c;
  }
  void rect(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) set(x, y, c);
  }
  void line(int x0, int y0, int x1, int y1, Rgb c, int thick = 1) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (;;) {
      rect(x0 - thick / 2, y0 - thick / 2, x0 + (thick - 1) / 2, y0 + (thick - 1) / 2, c);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * err;
      if (e2 >= dy) { err += dy; x0 += sx; }
      if (e2 <= dx) { err += dx; y0 += sy; }
    }
  }
  // 3x5 glyphs, 5 rows of 3 bits (MSB = left column).
  void text(int x, int y, const std::string& s, Rgb c, int scale = 2) {
    static const std::map<char, std::array<std::uint8_t, 5>> font = {
        {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
        {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 2, 2}},
        {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'A', {2, 5, 7, 5, 5}}, {'B', {6, 5, 6, 5, 6}},
        {'C', {3, 4, 4, 4, 3}}, {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}}, {'F', {7, 4, 6, 4, 4}},
        {'G', {3, 4, 5, 5, 3}}, {'H', {5, 5, 7, 5, 5}}, {'I', {7, 2, 2, 2, 7}}, {'J', {1, 1, 1, 5, 2}},
        {'K', {5, 5, 6, 5, 5}}, {'L', {4, 4, 4, 4, 7}}, {'M', {5, 7, 7, 5, 5}}, {'N', {6, 5, 5, 5, 5}},
        {'O', {2, 5, 5, 5, 2}}, {'P', {6, 5, 6, 4, 4}}, {'Q', {2, 5, 5, 6, 3}}, {'R', {6, 5, 6, 5, 5}},
        {'S', {3, 4, 2, 1, 6}}, {'T', {7, 2, 2, 2, 2}}, {'U', {5, 5, 5, 5, 7}}, {'V', {5, 5, 5, 5, 2}},
        {'W', {5, 5, 7, 7, 5}}, {'X', {5, 5, 2, 5, 5}}, {'Y', {5, 5, 2, 2, 2}}, {'Z', {7, 1, 2, 4, 7}},
        {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}}, {'/', {1, 1, 2, 4, 4}}, {'(', {1, 2, 2, 2, 1}},
        {')', {4, 2, 2, 2, 4}}, {':', {0, 2, 0, 2, 0}}, {'%', {5, 1, 2, 4, 5}}, {'=', {0, 7, 0, 7, 0}},
        {'+', {0, 2, 7, 2, 0}}, {',', {0, 0, 0, 2, 4}}, {'^', {2, 5, 0, 0, 0}}, {'_', {0, 0, 0, 0, 7}},
    };
    for (char ch : s) {
      const auto it = font.find(static_cast<char>(std::toupper(static_cast<unsigned char>(ch))));
      if (it != font.end())
        for (int r = 0; r < 5; ++r)
          for (int col = 0; col < 3; ++col)
            if (it->second[r] & (4 >> col)) rect(x + col * scale, y + r * scale, x + col * scale + scale - 1, y + r * scale + scale - 1, c);
      x += 4 * scale;
    }
  }
  static int textWidth(const std::string& s, int scale = 2) { return static_cast<int>(s.size()) * 4 * scale; }

  // Encoded through OutputFile (temporary file, every write checked, renamed into place).
  void writePng(const std::string& file) const {
    collide::cli::OutputFile out(file);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      throw std::runtime_error(file + ": cannot encode the PNG");
    }
    auto write = [](png_structp p, png_bytep data, png_size_t n) {
      static_cast<std::ostream*>(png_get_io_ptr(p))->write(reinterpret_cast<const char*>(data),
                                                          static_cast<std::streamsize>(n));
    };
    png_set_write_fn(png, &out.stream(), write, [](png_structp) {});
    png_set_IHDR(png, info, static_cast<png_uint_32>(w_), static_cast<png_uint_32>(h_), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < h_; ++y)
      png_write_row(png, reinterpret_cast<png_const_bytep>(&px_[static_cast<std::size_t>(y) * w_]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    out.commit();
  }

 private:
  int w_, h_;
  std::vector<Rgb> px_;
};

struct Series {
  bool log = true;
  std::string label;
  std::vector<double> x, y;
};

Series load(const std::string& spec) {
  // time|count:LABEL=FILE:COLUMN
  Series s;
  const auto colon = spec.find(':'), eq = spec.find('='), last = spec.rfind(':');
  if (colon == std::string::npos || eq == std::string::npos || last <= eq)
    throw std::runtime_error("bad series '" + spec + "': expected time|count:LABEL=FILE:COLUMN");
  const std::string kind = spec.substr(0, colon);
  if (kind != "time" && kind != "count") throw std::runtime_error("bad series kind '" + kind + "'");
  s.log = kind == "time";
  s.label = spec.substr(colon + 1, eq - colon - 1);
  const std::string file = spec.substr(eq + 1, last - eq - 1), column = spec.substr(last + 1);
  std::ifstream in = collide::util::openInput(file);  // a directory says so
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  {
    std::stringstream ss(line);
    std::string f;
    while (std::getline(ss, f, ',')) head.push_back(f);
  }
  const auto cx = std::find(head.begin(), head.end(), "step") - head.begin();
  const auto cy = std::find(head.begin(), head.end(), column) - head.begin();
  if (cy == static_cast<long>(head.size())) throw std::runtime_error(file + ": no column '" + column + "'");
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string v;
    while (std::getline(ss, v, ',')) f.push_back(v);
    if (static_cast<long>(f.size()) <= std::max(cx, cy)) continue;
    s.x.push_back(cx < static_cast<long>(head.size()) ? std::stod(f[cx]) : static_cast<double>(s.x.size()));
    s.y.push_back(std::stod(f[cy]));
  }
  return s;
}

std::string si(double v) {
  char b[32];
  if (v >= 1e9) std::snprintf(b, sizeof b, "%gS", v / 1e9);
  else if (v >= 1e6) std::snprintf(b, sizeof b, "%gMS", v / 1e6);
  else if (v >= 1e3) std::snprintf(b, sizeof b, "%gUS", v / 1e3);
  else std::snprintf(b, sizeof b, "%gNS", v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: collide-plot OUT.png TITLE time|count:LABEL=FILE:COLUMN...\n";
    return 1;
  }
  try {
    std::vector<Series> all;
    for (int k = 3; k < argc; ++k) all.push_back(load(argv[k]));
    const int W = 1000, H = 740, L = 110, R = 20, top1 = 70, h1 = 380, top2 = 500, h2 = 170;
    Image img(W, H);
    const Rgb ink{40, 40, 40}, grid{225, 225, 225};
    const Rgb palette[] = {{214, 39, 40}, {31, 119, 180}, {44, 160, 44}, {255, 127, 14}, {148, 103, 189}, {140, 86, 75}};
    img.text(10, 10, argv[2], ink, 3);

    double xmax = 1, tmin = 1e300, tmax = 0, cmax = 1;
    for (const auto& s : all) {
      for (std::size_t k = 0; k < s.x.size(); ++k) {
        xmax = std::max(xmax, s.x[k]);
        if (s.log && s.y[k] > 0) { tmin = std::min(tmin, s.y[k]); tmax = std::max(tmax, s.y[k]); }
        if (!s.log) cmax = std::max(cmax, s.y[k]);
      }
    }
    if (tmax <= 0) { tmin = 1; tmax = 10; }
    const double lo = std::floor(std::log10(tmin)), hi = std::max(lo + 1, std::ceil(std::log10(tmax)));
    const int plotW = W - L - R;
    auto X = [&](double x) { return L + static_cast<int>(std::lround(x / xmax * plotW)); };
    auto Y1 = [&](double v) { return top1 + h1 - static_cast<int>(std::lround((std::log10(v) - lo) / (hi - lo) * h1)); };
    auto Y2 = [&](double v) { return top2 + h2 - static_cast<int>(std::lround(v / cmax * h2)); };

    // Panels: grid, axes, tick labels.
    for (double e = lo; e <= hi; e += 1) {
      const int y = Y1(std::pow(10.0, e));
      img.line(L, y, W - R, y, grid);
      const std::string t = si(std::pow(10.0, e));
      img.text(L - 8 - Image::textWidth(t), y - 5, t, ink);
    }
    for (int k = 0; k <= 4; ++k) {
      const double v = cmax * k / 4;
      const int y = Y2(v);
      img.line(L, y, W - R, y, grid);
      char b[32];
      std::snprintf(b, sizeof b, "%.0f", v);
      img.text(L - 8 - Image::textWidth(b), y - 5, b, ink);
    }
    const double xstep = std::max(1.0, std::ceil(xmax / 10));
    for (double v = 0; v <= xmax; v += xstep) {
      char b[32];
      std::snprintf(b, sizeof b, "%.0f", v);
      img.line(X(v), top2 + h2, X(v), top2 + h2 + 4, ink);
      img.text(X(v) - Image::textWidth(b) / 2, top2 + h2 + 8, b, ink);
    }
    img.line(L, top1, L, top1 + h1, ink);
    img.line(L, top1 + h1, W - R, top1 + h1, ink);
    img.line(L, top2, L, top2 + h2, ink);
    img.line(L, top2 + h2, W - R, top2 + h2, ink);
    img.text(L - 100, top1 - 20, "TIME PER STEP (LOG)", ink);
    img.text(L - 100, top2 - 20, "PER STEP", ink);
    img.text(W / 2 - 20, H - 22, "STEP", ink);

    // Series and legend.
    int legendY1 = top1 + 8, legendY2 = top2 + 8;
    for (std::size_t k = 0; k < all.size(); ++k) {
      const auto& s = all[k];
      const Rgb c = palette[k % 6];
      bool have = false;
      int px = 0, py = 0;
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (s.log && !(s.y[i] > 0)) { have = false; continue; }
        const int x = X(s.x[i]), y = s.log ? Y1(s.y[i]) : Y2(s.y[i]);
        if (have) img.line(px, py, x, y, c, 2);
        else img.rect(x - 1, y - 1, x + 1, y + 1, c);
        px = x; py = y; have = true;
      }
      int& ly = s.log ? legendY1 : legendY2;
      const int lx = W - R - 330;
      img.rect(lx, ly + 2, lx + 16, ly + 7, c);
      img.text(lx + 24, ly, s.label, ink);
      ly += 16;
    }
    img.writePng(argv[1]);
    std::cout << "collide-plot: wrote " << argv[1] << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "collide-plot: " << e.what() << "\n";
    return 1;
  }
}
