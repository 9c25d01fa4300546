#include "freeturn/report/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "freeturn/io/atomic_file.hpp"
#include "report_text.hpp"

namespace freeturn {
namespace {

using detail::num;



std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}


std::string html_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else
      out += ch;
  }
  return out;
}

// A polyline plot of (x, y) pairs scaled into a w × h box, with axis labels.
// scatter: dots (values along the radius from a spiral), else a line.
// An 8-bit palette BMP (browsers show it in an SVG <image>): index 0 is "no data", 1…255
// run from blue (−limit) through white (0) to red (+limit).
std::string bmp_heat_map(const ResidualHeatMap& m, double limit) {
  const int n = m.size, row = (n + 3) / 4 * 4;
  const std::uint32_t offset = 14 + 40 + 1024, image = static_cast<std::uint32_t>(row * n);
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
  u32(static_cast<std::uint32_t>(n));
  u32(static_cast<std::uint32_t>(-n));  // negative height: rows top-down
  u16(1);
  u16(8);
  u32(0);
  u32(image);
  u32(2835);
  u32(2835);
  u32(256);
  u32(0);
  const auto bgr = [&](int blue, int green, int red) {
    b += static_cast<char>(blue);
    b += static_cast<char>(green);
    b += static_cast<char>(red);
    b += '\0';
  };
  bgr(244, 244, 244);
  for (int k = 1; k < 256; ++k) {
    const double t = (k - 1) / 254.0 * 2 - 1;  // −1 … 1
    const int fade = static_cast<int>(std::lround(255 * (1 - std::abs(t))));
    if (t < 0)
      bgr(255, fade, fade);
    else
      bgr(fade, fade, 255);
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const double v = m.mean[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) +
                              static_cast<std::size_t>(x)];
      int index = 0;
      if (!std::isnan(v))
        index = 1 + static_cast<int>(std::lround((std::clamp(v / limit, -1.0, 1.0) + 1) / 2 * 254));
      b += static_cast<char>(index);
    }
    b.append(static_cast<std::size_t>(row - n), '\0');
  }
  return b;
}

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

// The residual map with a colour bar in nm, symmetric about 0 and as wide as the
// figures' extremes (the margin's uncut edge, left out of the figures, is clipped).
std::string svg_heat_map(const ResidualHeatMap& m, double max, double min) {
  const double limit = std::max({std::abs(max), std::abs(min), 1e-9});
  const int side = 360, bar_x = side + 30;
  std::string svg =
      "<figure><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(side + 170) +
      "\" height=\"" + num(side + 20) +
      "\"><defs><linearGradient id=\"residual\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">"
      "<stop offset=\"0\" stop-color=\"#0000ff\"/><stop offset=\"0.5\" stop-color=\"#ffffff\"/>"
      "<stop offset=\"1\" stop-color=\"#ff0000\"/></linearGradient></defs>";
  svg += "<image x=\"10\" y=\"10\" width=\"" + num(side) + "\" height=\"" + num(side) +
         "\" style=\"image-rendering:pixelated\" href=\"data:image/bmp;base64," +
         base64(bmp_heat_map(m, limit)) + "\"/>";
  svg += "<rect x=\"" + num(bar_x) + "\" y=\"10\" width=\"16\" height=\"" + num(side) +
         "\" fill=\"url(#residual)\" stroke=\"#ccc\"/>";
  const auto label = [&](double y, double value) {
    svg += "<text x=\"" + num(bar_x + 22) + "\" y=\"" + num(y + 4) + "\" font-size=\"12\">" +
           num(value * 1e6) + " nm</text>";
  };
  label(10, limit);
  label(10 + side / 2.0, 0);
  label(10 + side, -limit);
  svg += "</svg><figcaption>Simulated residual seen from above, mean per pixel (" +
         num(2 * m.half_width / m.size * 1e3) +
         " µm): red above the design, blue below; colours clipped at the figures' "
         "extremes</figcaption></figure>\n";
  return svg;
}

std::string svg_plot(const std::vector<std::pair<double, double>>& xy, const std::string& title,
                     const std::string& x_label, const std::string& y_label, bool equal_axes,
                     bool scatter = false) {
  const double w = 560, h = 320, m = 48;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& [x, y] : xy) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  if (xy.empty() || !(x1 > x0)) {
    x0 = 0;
    x1 = 1;
  }
  if (xy.empty() || !(y1 > y0)) {
    y0 = std::min(0.0, y0 == 1e300 ? 0.0 : y0);
    y1 = y0 + 1;
  }
  double sx = (w - 2 * m) / (x1 - x0), sy = (h - 2 * m) / (y1 - y0);
  if (equal_axes) sx = sy = std::min(sx, sy);
  std::string path;
  char buf[64];
  for (const auto& [x, y] : xy) {
    std::snprintf(buf, sizeof buf, scatter ? "M%.1f %.1fh0 " : "%.1f,%.1f ", m + (x - x0) * sx,
                  h - m - (y - y0) * sy);
    path += buf;
  }
  std::string svg = "<figure><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(w) +
                    "\" height=\"" + num(h) + "\" viewBox=\"0 0 " + num(w) + " " + num(h) + "\">";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" fill=\"#fff\" stroke=\"#ccc\"/>";
  svg += scatter ? "<path fill=\"none\" stroke=\"#1f5fa8\" stroke-width=\"2\" "
                   "stroke-linecap=\"round\" d=\"" +
                       path + "\"/>"
                 : "<polyline fill=\"none\" stroke=\"#1f5fa8\" stroke-width=\"0.7\" points=\"" +
                       path + "\"/>";
  svg += "<text x=\"" + num(w / 2) + "\" y=\"" + num(h - 10) +
         "\" text-anchor=\"middle\" font-size=\"12\">" + html_escape(x_label) + " (" + num(x0) +
         " … " + num(x1) + ")</text>";
  svg += "<text x=\"12\" y=\"" + num(h / 2) + "\" font-size=\"12\" transform=\"rotate(-90 12 " +
         num(h / 2) + ")\" text-anchor=\"middle\">" + html_escape(y_label) + " (" + num(y0) +
         " … " + num(y1) + ")</text>";
  svg += "</svg><figcaption>" + html_escape(title) + "</figcaption></figure>\n";
  return svg;
}

}  // namespace

void write_report(const RunReport& r, const std::string& json_path, const std::string& html_path,
                  OutputSet& outputs) {
  std::string j =
      "{\n  \"job\": " + json_string(r.job) + ",\n  \"job_file\": " + json_string(r.job_file) +
      ",\n  \"job_yaml\": " + json_string(r.job_text) +
      ",\n  \"machine\": " + json_string(r.machine) + ",\n  \"plugin\": " + json_string(r.plugin) +
      ",\n  \"alpha_max_deg\": " + (r.alpha_max_deg < 0 ? "null" : num(r.alpha_max_deg)) +
      ",\n  \"axis_moved\": " + (r.axis_moved ? "true" : "false") +
      ",\n  \"verdict\": " + (r.unsafe.empty() ? "\"PASS\"" : "\"UNSAFE\"") + ", \"unsafe\": [";
  for (std::size_t i = 0; i < r.unsafe.size(); ++i) j += (i ? ", " : "") + json_string(r.unsafe[i]);
  j += "],\n  \"timing\": {\"scheduled\": " + std::string(r.scheduled ? "true" : "false") +
       ", \"spindle_rpm\": " + num(r.spindle_rpm) + ", \"requested_rpm\": " + num(r.requested_rpm) +
       ", \"enforce_dynamics\": " + (r.enforce_dynamics ? "true" : "false") + "}" +
       ",\n  \"warnings\": [";
  for (std::size_t i = 0; i < r.warnings.size(); ++i)
    j += (i ? ", " : "") + json_string(r.warnings[i]);
  j += "],\n  \"passes\": [";
  static const char* const kAxes[4] = {"X", "Z", "C", "B"};
  for (std::size_t p = 0; p < r.passes.size(); ++p) {
    const PassFigures& f = r.passes[p];
    j += std::string(p ? "," : "") + "\n    {\"name\": " + json_string(f.name) +
         ", \"stock_mm\": " + num(f.stock) + ", \"points\": " + std::to_string(f.points) +
         ", \"revolutions\": " + num(f.revolutions) +
         ",\n     \"chord_error_mm\": {\"max\": " + num(f.chord_max) +
         ", \"rms\": " + num(f.chord_rms) + "}, \"scallop_mm\": {\"max\": " + num(f.scallop_max) +
         ", \"rms\": " + num(f.scallop_rms) + "},\n     \"cycle_time_s\": " + num(f.cycle_time) +
         ", \"max_rpm\": " + num(f.dynamics.max_rpm) +
         ", \"max_rpm_limited_by\": " + json_string(f.dynamics.limiting) +
         ", \"constant_rpm_cycle_time_s\": " + num(f.constant_rpm_cycle_time) +
         ", \"slowed_blocks\": " + std::to_string(f.slowed_blocks) +
         ",\n     \"uncut_residual\": {\"held_points\": " + std::to_string(f.held_points) +
         ", \"max_mm\": " + num(f.uncut_max) +
         ", \"at_theta_deg\": " + num(f.uncut_theta * 180 / std::numbers::pi) +
         ", \"at_r_mm\": " + num(f.uncut_r) + ", \"band_width_mm\": " + num(f.band_width) +
         ", \"max_by_band_mm\": [" +
         [&] {
           std::string b;
           for (std::size_t k = 0; k < f.uncut_by_band.size(); ++k)
             b += (k ? ", " : "") + num(f.uncut_by_band[k]);
           return b;
         }() +
         "]}" + ",\n     \"peak_velocity\": {";
    for (int a = 0; a < 4; ++a)
      j += std::string(a ? ", " : "") + "\"" + kAxes[a] + "\": " + num(f.dynamics.peak_velocity[a]);
    j += "}, \"peak_acceleration\": {";
    for (int a = 0; a < 4; ++a)
      j += std::string(a ? ", " : "") + "\"" + kAxes[a] +
           "\": " + num(f.dynamics.peak_acceleration[a]);
    j += "}, \"peak_block_rate\": " + num(f.dynamics.peak_block_rate) + ",\n     \"checks\": {";
    for (int c = 0; c < kToolCheckCount; ++c) {
      const CheckFinding& k = f.checks.findings[c];
      j += std::string(c ? ", " : "") + json_string(tool_check_name(static_cast<ToolCheck>(c))) +
           ": {\"violations\": " + std::to_string(k.count) + ", \"worst\": " + num(k.worst) + "}";
    }
    j += "}}";
  }
  j += "\n  ]";
  if (r.simulation) {
    const SimulationResult& s = *r.simulation;
    j += ",\n  \"simulation\": {\"pv_mm\": " + num(s.pv) + ", \"rms_mm\": " + num(s.rms) +
         ", \"max_mm\": " + num(s.max) + ", \"min_mm\": " + num(s.min) +
         ", \"max_at_r_mm\": " + num(s.max_r) + ", \"min_at_r_mm\": " + num(s.min_r) +
         ", \"cells\": " + std::to_string(static_cast<long>(s.rings) * s.columns) +
         ", \"uncut_cells\": " + std::to_string(s.uncut) +
         ",\n    \"predicted\": {\"pv_mm\": " + num(s.predicted.pv()) +
         ", \"max_mm\": " + num(s.predicted.max()) + ", \"min_mm\": " + num(s.predicted.min()) +
         ", \"max_scallop_mm\": " + num(s.predicted.max_scallop) +
         ", \"max_uncut_mm\": " + num(s.predicted.max_uncut) +
         ", \"max_chord_above_mm\": " + num(s.predicted.max_chord_above) +
         ", \"max_chord_below_mm\": " + num(s.predicted.max_chord_below) +
         ", \"pv_ratio\": " + num(s.pv > 0 ? s.predicted.pv() / s.pv : 0) + "},\n    \"worst\": [";
    for (std::size_t k = 0; k < s.worst.size(); ++k)
      j += std::string(k ? ", " : "") + "{\"r_mm\": " + num(s.worst[k].r) +
           ", \"theta_deg\": " + num(s.worst[k].phi * 180 / std::numbers::pi) +
           ", \"residual_mm\": " + num(s.worst[k].residual) +
           ", \"cause\": " + json_string(to_string(s.worst[k].cause)) + "}";
    j += "]}";
  }
  j += "\n}\n";
  outputs.add(json_path).write(j);

  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>freeturn: " +
      html_escape(r.job) +
      "</title><style>body{font-family:sans-serif;max-width:1200px;margin:2em auto;color:#222}"
      "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}"
      "th{text-align:left}figure{display:inline-block;margin:8px}.warn{color:#a15c00}.unsafe{color:"
      "#b00020}.pass{color:#1b7a1b}</style></"
      "head><body>\n";
  h += "<h1>" + html_escape(r.job) + " on " + html_escape(r.machine) + "</h1>\n";
  if (r.alpha_max_deg >= 0)
    h += "<p>Quasi-revolution angle on the base: α<sub>max</sub> = " + num(r.alpha_max_deg) +
         "°</p>\n";
  if (r.unsafe.empty()) {
    h += "<p class=\"pass\"><b>PASS</b>: every check passed; the program stays within the "
         "machine's limits.</p>\n";
  } else {
    h += "<p class=\"unsafe\"><b>UNSAFE</b>: do not cut this program as it is.</p>\n<ul>";
    for (const std::string& u : r.unsafe) h += "<li class=\"unsafe\">" + html_escape(u) + "</li>";
    h += "</ul>\n";
  }
  for (const std::string& w : r.warnings) h += "<p class=\"warn\">" + html_escape(w) + "</p>\n";
  h += "<table><tr><th>pass</th><th>points</th><th>revolutions</th><th>chord max "
       "(nm)</th><th>chord rms (nm)</th>"
       "<th>scallop max (nm)</th><th>uncut at creases, max (nm)</th><th>cycle as programmed "
       "(s)</th><th>cycle at one constant rpm (s)</th><th>max constant rpm</th></tr>\n";
  for (const PassFigures& f : r.passes)
    h += "<tr><th>" + html_escape(f.name) + "</th><td>" + std::to_string(f.points) + "</td><td>" +
         num(f.revolutions) + "</td><td>" + num(f.chord_max * 1e6) + "</td><td>" +
         num(f.chord_rms * 1e6) + "</td><td>" + num(f.scallop_max * 1e6) + "</td><td>" +
         num(f.uncut_max * 1e6) + "</td><td>" + num(f.cycle_time) + "</td><td>" +
         num(f.constant_rpm_cycle_time) + "</td><td>" + num(f.dynamics.max_rpm) + "</td></tr>\n";
  h += "</table>\n";
  if (r.simulation) {
    const SimulationResult& s = *r.simulation;
    const double ratio = s.pv > 0 ? s.predicted.pv() / s.pv : 0;
    h += "<h2>Simulated cut</h2>\n<p>Form error of the finishing pass: PV " + num(s.pv * 1e6) +
         " nm, RMS " + num(s.rms * 1e6) + " nm (residual grid " + std::to_string(s.rings) + " × " +
         std::to_string(s.columns) + "). The planner predicted PV " + num(s.predicted.pv() * 1e6) +
         " nm: " + num(ratio) + "× the simulation" +
         (ratio < 1      ? " (<span class=\"warn\">not an upper bound</span>)"
          : ratio <= 1.1 ? " (an upper bound within 10%)"
                         : " (an upper bound, loose by more than 10%)") +
         ".</p>\n";
    h += "<table><tr><th>worst place</th><th>r (mm)</th><th>θ (°)</th><th>residual "
         "(nm)</th><th>cause</th></tr>\n";
    for (std::size_t k = 0; k < s.worst.size(); ++k)
      h += "<tr><th>" + std::to_string(k + 1) + "</th><td>" + num(s.worst[k].r) + "</td><td>" +
           num(s.worst[k].phi * 180 / std::numbers::pi) + "</td><td>" +
           num(s.worst[k].residual * 1e6) + "</td><td>" + to_string(s.worst[k].cause) +
           "</td></tr>\n";
    h += "</table>\n";
    if (r.heat_map) h += svg_heat_map(*r.heat_map, s.max, s.min);
  }
  const PassFigures& f = r.passes.back();
  std::vector<std::pair<double, double>> top, error;
  for (const PlotPoint& p : f.samples) {
    top.emplace_back(p.x, p.y);
    error.emplace_back(p.r, p.chord * 1e6);
  }
  h += svg_plot(
      top, "The finishing path seen from above (every " + std::to_string(f.stride) + "th point)",
      "x (mm)", "y (mm)", true);
  h += svg_plot(error, "Predicted chord error along the radius", "r (mm)", "chord error (nm)",
                false, true);
  std::vector<std::pair<double, double>> per_rev, vx, vz;
  for (std::size_t k = 0; k < f.points_per_revolution.size(); ++k)
    per_rev.emplace_back(static_cast<double>(k), static_cast<double>(f.points_per_revolution[k]));
  for (const PlotPoint& p : f.samples) {
    vx.emplace_back(p.r, p.vx);
    vz.emplace_back(p.r, p.vz);
  }
  h += svg_plot(per_rev, "Points per revolution", "revolution", "points", false);
  h += svg_plot(vx, "X velocity along the radius", "r (mm)", "X velocity (mm/s)", false, true);
  h += svg_plot(vz, "Z velocity along the radius", "r (mm)", "Z velocity (mm/s)", false, true);
  h += "</body></html>\n";
  outputs.add(html_path).write(h);
}

}  // namespace freeturn
