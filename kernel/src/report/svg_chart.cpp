#include "svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "freeturn/core/number_text.hpp"
#include "freeturn/core/utf8.hpp"

namespace freeturn::detail {
namespace {

std::string px(double v) { return fixed_text(v, 1); }

std::string base64(const std::string& in) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t a = static_cast<unsigned char>(in[i]);
    const std::uint32_t b = i + 1 < in.size() ? static_cast<unsigned char>(in[i + 1]) : 0;
    const std::uint32_t c = i + 2 < in.size() ? static_cast<unsigned char>(in[i + 2]) : 0;
    const std::uint32_t v = a << 16 | b << 8 | c;
    out += digits[v >> 18 & 63];
    out += digits[v >> 12 & 63];
    out += i + 1 < in.size() ? digits[v >> 6 & 63] : '=';
    out += i + 2 < in.size() ? digits[v & 63] : '=';
  }
  return out;
}

}  // namespace

std::string html_escape(const std::string& text) {
  const std::string s = valid_utf8(text);  // the page is UTF-8, whatever the text held
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    switch (ch) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string readable(double value, int decimals) {
  if (!std::isfinite(value)) return "–";
  if (std::abs(value) < 0.5 * std::pow(10.0, -decimals)) value = 0;  // no "−0.0"
  const std::string text = fixed_text(value, std::max(0, decimals));
  return text[0] == '-' ? "−" + text.substr(1) : text;
}

Ticks nice_ticks(double lo, double hi, int count) {
  Ticks t;
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (!(hi > lo)) {
    const double pad = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / std::max(count, 2);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double step = (fraction <= 1 ? 1 : fraction <= 2 ? 2 : fraction <= 5 ? 5 : 10) * power;
  t.lo = std::floor(lo / step + 1e-9) * step;
  t.hi = std::ceil(hi / step - 1e-9) * step;
  t.decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  for (double v = t.lo; v <= t.hi + step * 1e-6; v += step) t.values.push_back(v);
  return t;
}

std::string svg_chart(const Chart& c) {
  const double w = c.width, h = c.height, left = 64, right = 16, top = 16, bottom = 44;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const ChartSeries& s : c.series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x);
      y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  // A limit far beyond the data (a 50 mm/s limit over 0.02 mm/s moves) would flatten it:
  // such a line is named, not drawn.
  const double data_size = y0 <= y1 ? std::max(std::abs(y0), std::abs(y1)) : 0.0;
  std::vector<const ChartLine*> drawn, beyond;
  for (const ChartLine& l : c.horizontal) {
    if (!std::isfinite(l.at)) continue;
    if (data_size > 0 && std::abs(l.at) > 4 * data_size) {
      beyond.push_back(&l);
      continue;
    }
    drawn.push_back(&l);
    y0 = std::min(y0, l.at), y1 = std::max(y1, l.at);
  }
  if (c.y_from_zero) y0 = std::min(y0, 0.0), y1 = std::max(y1, 0.0);
  if (x0 > x1) x0 = 0, x1 = 1;
  if (y0 > y1) y0 = 0, y1 = 1;
  const Ticks tx = nice_ticks(x0, x1), ty = nice_ticks(y0, y1, 5);
  const double plot_w = w - left - right, plot_h = h - top - bottom;
  const auto X = [&](double x) { return left + (x - tx.lo) / (tx.hi - tx.lo) * plot_w; };
  const auto Y = [&](double y) { return top + plot_h - (y - ty.lo) / (ty.hi - ty.lo) * plot_h; };
  std::string svg = "<figure id=\"" + c.id + "\"><svg xmlns=\"http://www.w3.org/2000/svg\" "
                    "width=\"" + px(w) + "\" height=\"" + px(h) + "\" viewBox=\"0 0 " + px(w) +
                    " " + px(h) + "\" role=\"img\" aria-label=\"" + html_escape(c.title) + "\">";
  svg += "<rect x=\"" + px(left) + "\" y=\"" + px(top) + "\" width=\"" + px(plot_w) +
         "\" height=\"" + px(plot_h) + "\" fill=\"#fff\" stroke=\"#888\"/>";
  for (const double v : tx.values) {
    svg += "<line class=\"grid\" x1=\"" + px(X(v)) + "\" y1=\"" + px(top) + "\" x2=\"" + px(X(v)) +
           "\" y2=\"" + px(top + plot_h) + "\"/>";
    svg += "<text x=\"" + px(X(v)) + "\" y=\"" + px(top + plot_h + 14) +
           "\" text-anchor=\"middle\">" + readable(v, tx.decimals) + "</text>";
  }
  for (const double v : ty.values) {
    svg += "<line class=\"grid\" x1=\"" + px(left) + "\" y1=\"" + px(Y(v)) + "\" x2=\"" +
           px(left + plot_w) + "\" y2=\"" + px(Y(v)) + "\"/>";
    svg += "<text x=\"" + px(left - 4) + "\" y=\"" + px(Y(v) + 4) + "\" text-anchor=\"end\">" +
           readable(v, ty.decimals) + "</text>";
  }
  svg += "<text x=\"" + px(left + plot_w / 2) + "\" y=\"" + px(h - 8) +
         "\" text-anchor=\"middle\" class=\"title\">" + html_escape(c.x_title) + "</text>";
  svg += "<text x=\"14\" y=\"" + px(top + plot_h / 2) + "\" transform=\"rotate(-90 14 " +
         px(top + plot_h / 2) + ")\" text-anchor=\"middle\" class=\"title\">" +
         html_escape(c.y_title) + "</text>";
  for (const ChartSeries& s : c.series) {
    std::string d;
    d.reserve(s.points.size() * 16);
    bool pen = false;
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y)) {
        pen = false;
        continue;
      }
      d += s.dots ? "M" + px(X(x)) + " " + px(Y(y)) + "h0"
                  : (pen ? "L" : "M") + px(X(x)) + " " + px(Y(y));
      pen = true;
    }
    svg += s.dots ? "<path fill=\"none\" stroke=\"" + s.colour +
                        "\" stroke-width=\"2.2\" stroke-linecap=\"round\" d=\"" + d + "\"/>"
                  : "<path fill=\"none\" stroke=\"" + s.colour +
                        "\" stroke-width=\"1.3\" stroke-linejoin=\"round\" d=\"" + d + "\"/>";
  }
  for (const ChartLine* line : drawn) {
    const ChartLine& l = *line;
    svg += "<line x1=\"" + px(left) + "\" y1=\"" + px(Y(l.at)) + "\" x2=\"" + px(left + plot_w) +
           "\" y2=\"" + px(Y(l.at)) + "\" stroke=\"" + l.colour +
           "\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>";
    svg += "<text x=\"" + px(left + plot_w - 4) + "\" y=\"" + px(Y(l.at) - 4) +
           "\" text-anchor=\"end\" fill=\"" + l.colour + "\">" + html_escape(l.label) + "</text>";
  }
  for (const ChartLine& l : c.vertical) {
    if (!std::isfinite(l.at) || l.at < tx.lo || l.at > tx.hi) continue;
    svg += "<line x1=\"" + px(X(l.at)) + "\" y1=\"" + px(top) + "\" x2=\"" + px(X(l.at)) +
           "\" y2=\"" + px(top + plot_h) + "\" stroke=\"" + l.colour +
           "\" stroke-width=\"1.2\"/><text x=\"" + px(X(l.at) + 3) + "\" y=\"" + px(top + 12) +
           "\" fill=\"" + l.colour + "\">" + html_escape(l.label) + "</text>";
  }
  double by = top + 14;
  for (const ChartLine* l : beyond) {
    svg += "<text x=\"" + px(left + plot_w - 4) + "\" y=\"" + px(by) + "\" text-anchor=\"end\" fill=\"" +
           l->colour + "\">" + html_escape(l->label) + " (" + (l->at > 0 ? "above" : "below") +
           " the chart)</text>";
    by += 14;
  }
  // The legend, top left inside the plot.
  double ly = top + 14;
  for (const ChartSeries& s : c.series) {
    if (s.label.empty()) continue;
    svg += "<rect x=\"" + px(left + 8) + "\" y=\"" + px(ly - 8) +
           "\" width=\"10\" height=\"10\" fill=\"" + s.colour + "\"/><text x=\"" + px(left + 22) +
           "\" y=\"" + px(ly + 1) + "\">" + html_escape(s.label) + "</text>";
    ly += 14;
  }
  svg += "</svg><figcaption>" + html_escape(c.title) + "</figcaption></figure>\n";
  return svg;
}

namespace {

// The 54-byte BMP header of a size × size image, rows top-down, `bits` per pixel, with
// `colours` palette entries after it.
std::string bmp_header(int size, int bits, int colours, std::uint32_t image) {
  const std::uint32_t offset = 14 + 40 + 4 * static_cast<std::uint32_t>(colours);
  std::string b;
  const auto u16 = [&](std::uint32_t v) {
    b += static_cast<char>(v & 255);
    b += static_cast<char>((v >> 8) & 255);
  };
  const auto u32 = [&](std::uint32_t v) {
    u16(v & 0xffff);
    u16(v >> 16);
  };
  b += "BM";
  u32(offset + image);
  u32(0);
  u32(offset);
  u32(40);
  u32(static_cast<std::uint32_t>(size));
  u32(static_cast<std::uint32_t>(-size));  // negative height: rows top-down
  u16(1);
  u16(static_cast<std::uint32_t>(bits));
  u32(0);
  u32(image);
  u32(2835);
  u32(2835);
  u32(static_cast<std::uint32_t>(colours));
  u32(0);
  return b;
}

}  // namespace

std::string bmp_rgb_data_url(const std::vector<unsigned char>& rgb, int size) {
  const int row = (3 * size + 3) / 4 * 4;
  std::string b = bmp_header(size, 24, 0, static_cast<std::uint32_t>(row * size));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                             static_cast<std::size_t>(x)) * 3;
      b += static_cast<char>(rgb[k + 2]);  // BGR
      b += static_cast<char>(rgb[k + 1]);
      b += static_cast<char>(rgb[k]);
    }
    b.append(static_cast<std::size_t>(row - 3 * size), '\0');
  }
  return "data:image/bmp;base64," + base64(b);
}

std::string bmp_indexed_data_url(const std::vector<unsigned char>& index,
                                 const std::vector<unsigned char>& palette_rgb, int size) {
  const int row = (size + 3) / 4 * 4;
  std::string b = bmp_header(size, 8, 256, static_cast<std::uint32_t>(row * size));
  for (std::size_t k = 0; k < 256; ++k) {
    b += static_cast<char>(palette_rgb[3 * k + 2]);
    b += static_cast<char>(palette_rgb[3 * k + 1]);
    b += static_cast<char>(palette_rgb[3 * k]);
    b += '\0';
  }
  for (int y = 0; y < size; ++y) {
    b.append(reinterpret_cast<const char*>(index.data()) + static_cast<std::size_t>(y) * static_cast<std::size_t>(size),
             static_cast<std::size_t>(size));
    b.append(static_cast<std::size_t>(row - size), '\0');
  }
  return "data:image/bmp;base64," + base64(b);
}

}  // namespace freeturn::detail
