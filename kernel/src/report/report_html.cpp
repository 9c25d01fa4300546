// report.html: what an engineer looks at before cutting (docs/report.md). The summary
// and the verdict first, then the part and its path, the predicted form error split into
// figure and finish, and the values along the radius against their limits.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "freeturn/core/number_text.hpp"
#include "freeturn/surface/zernike.hpp"
#include "report_writers.hpp"
#include "svg_chart.hpp"

namespace freeturn::detail {
namespace {

constexpr double kDegrees = 180 / std::numbers::pi;
constexpr int kPartPixels = 280;
constexpr int kMapPixels = 240;  // the correction maps, per side
constexpr const char* kAxes[4] = {"X", "Z", "C", "B"};

using Rgb = std::array<double, 3>;

// A perceptually ordered palette (dark blue → green → yellow), for heights.
Rgb sequential(double t) {
  static const Rgb stops[] = {{0.27, 0.00, 0.33}, {0.23, 0.32, 0.55}, {0.13, 0.57, 0.55},
                              {0.37, 0.79, 0.38}, {0.99, 0.91, 0.15}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  Rgb c;
  for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)] = stops[i][static_cast<std::size_t>(k)] * (1 - f) + stops[i + 1][static_cast<std::size_t>(k)] * f;
  return c;
}

// Blue (−1) through white (0) to red (+1), for errors about the design.
Rgb diverging(double t) {
  t = std::clamp(t, -1.0, 1.0);
  const double fade = 1 - std::abs(t);
  return t < 0 ? Rgb{fade, fade, 1.0} : Rgb{1.0, fade, fade};
}

void put_pixel(std::vector<unsigned char>& rgb, std::size_t k, const Rgb& c) {
  for (std::size_t i = 0; i < 3; ++i)
    rgb[3 * k + i] = static_cast<unsigned char>(std::lround(std::clamp(c[i], 0.0, 1.0) * 255));
}

std::string duration(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "–";
  const long s = std::lround(seconds);
  const long h = s / 3600, m = s / 60 % 60, r = s % 60;
  return std::to_string(h) + ":" + (m < 10 ? "0" : "") + std::to_string(m) + ":" +
         (r < 10 ? "0" : "") + std::to_string(r);
}

std::string nm(double mm) { return readable(mm * 1e6, 1) + " nm"; }

// A square map of [−half, half]² with x and y axes in mm, an optional overlay (SVG in the
// image's pixel frame), and a colour bar from `low` to `high` labelled in `unit`.
std::string map_figure(const std::string& id, const std::string& caption, const std::string& image,
                       int pixels, double half, const std::string& overlay, Rgb (*palette)(double),
                       bool diverging_bar, double low, double high, const std::string& unit,
                       int decimals) {
  const double side = 360, left = 56, top = 12, bar_x = left + side + 18;
  const double scale = side / pixels;
  std::string svg = "<figure id=\"" + id + "\"><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                    readable(bar_x + 96, 0) + "\" height=\"" + readable(top + side + 44, 0) +
                    "\" role=\"img\" aria-label=\"" + html_escape(caption) + "\">";
  svg += "<image x=\"" + readable(left, 1) + "\" y=\"" + readable(top, 1) + "\" width=\"" +
         readable(side, 1) + "\" height=\"" + readable(side, 1) +
         "\" preserveAspectRatio=\"none\" href=\"" + image + "\"/>";
  if (!overlay.empty())
    svg += "<g transform=\"translate(" + readable(left, 1) + " " + readable(top, 1) + ") scale(" +
           fixed_text(scale, 6) + ")\">" + overlay + "</g>";
  svg += "<rect x=\"" + readable(left, 1) + "\" y=\"" + readable(top, 1) + "\" width=\"" +
         readable(side, 1) + "\" height=\"" + readable(side, 1) + "\" fill=\"none\" stroke=\"#888\"/>";
  const Ticks t = nice_ticks(-half, half, 6);
  for (const double v : t.values) {
    if (v < -half - 1e-12 || v > half + 1e-12) continue;
    const double xp = left + (v + half) / (2 * half) * side, yp = top + (half - v) / (2 * half) * side;
    svg += "<line class=\"tick\" x1=\"" + readable(xp, 1) + "\" y1=\"" + readable(top + side, 1) +
           "\" x2=\"" + readable(xp, 1) + "\" y2=\"" + readable(top + side + 5, 1) + "\"/>";
    svg += "<text x=\"" + readable(xp, 1) + "\" y=\"" + readable(top + side + 17, 1) +
           "\" text-anchor=\"middle\">" + readable(v, t.decimals) + "</text>";
    svg += "<line class=\"tick\" x1=\"" + readable(left - 5, 1) + "\" y1=\"" + readable(yp, 1) +
           "\" x2=\"" + readable(left, 1) + "\" y2=\"" + readable(yp, 1) + "\"/>";
    svg += "<text x=\"" + readable(left - 8, 1) + "\" y=\"" + readable(yp + 4, 1) +
           "\" text-anchor=\"end\">" + readable(v, t.decimals) + "</text>";
  }
  svg += "<text x=\"" + readable(left + side / 2, 1) + "\" y=\"" + readable(top + side + 36, 1) +
         "\" text-anchor=\"middle\" class=\"title\">x (mm)</text>";
  svg += "<text x=\"14\" y=\"" + readable(top + side / 2, 1) + "\" transform=\"rotate(-90 14 " +
         readable(top + side / 2, 1) + ")\" text-anchor=\"middle\" class=\"title\">y (mm)</text>";
  // The colour bar: 64 steps of the palette, labelled at its ends and middle.
  for (int k = 0; k < 64; ++k) {
    const double f = (k + 0.5) / 64;
    const Rgb c = palette(diverging_bar ? 2 * f - 1 : f);
    svg += "<rect x=\"" + readable(bar_x, 1) + "\" y=\"" + readable(top + side * (1 - (k + 1) / 64.0), 2) +
           "\" width=\"14\" height=\"" + readable(side / 64 + 0.6, 2) + "\" fill=\"rgb(" +
           std::to_string(std::lround(c[0] * 255)) + "," + std::to_string(std::lround(c[1] * 255)) +
           "," + std::to_string(std::lround(c[2] * 255)) + ")\"/>";
  }
  svg += "<rect x=\"" + readable(bar_x, 1) + "\" y=\"" + readable(top, 1) + "\" width=\"14\" height=\"" +
         readable(side, 1) + "\" fill=\"none\" stroke=\"#888\"/>";
  const auto bar_label = [&](double y, double v) {
    svg += "<text x=\"" + readable(bar_x + 18, 1) + "\" y=\"" + readable(y + 4, 1) + "\">" +
           readable(v, decimals) + " " + unit + "</text>";
  };
  bar_label(top, high);
  bar_label(top + side / 2, (low + high) / 2);
  bar_label(top + side, low);
  svg += "</svg><figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
  return svg;
}

// The design's height over the aperture, coloured by height and shaded by its slope (light
// from the upper left), so the small features on a large sag (lenslets) show.
std::string part_image(const Surface& design, double inner, double outer, double& low, double& high) {
  const int n = kPartPixels;
  std::vector<double> z(static_cast<std::size_t>(n) * n, std::nan(""));
  low = 1e300, high = -1e300;
  double slope_scale = 0;
  std::vector<std::array<double, 2>> gradient(z.size());
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      const double x = -outer + (px + 0.5) * 2 * outer / n, y = outer - (py + 0.5) * 2 * outer / n;
      const double r = std::hypot(x, y);
      if (r > outer || r < inner) continue;
      double h, hx, hy;
      design.sag_gradient(x, y, h, hx, hy);
      if (!std::isfinite(h)) continue;
      const std::size_t k = static_cast<std::size_t>(py) * n + static_cast<std::size_t>(px);
      z[k] = h;
      gradient[k] = {hx, hy};
      low = std::min(low, h), high = std::max(high, h);
    }
  if (low > high) low = high = 0;
  // Shading from each pixel's slope less its neighbourhood's (7 × 7 px): the features, not
  // the bowl (the base sphere's slope would drown the lenslets' own). The largest such
  // slope sets the shading's contrast.
  std::vector<double> detail(z.size(), 0.0);
  for (int py = 1; py + 1 < n; ++py)
    for (int px = 1; px + 1 < n; ++px) {
      const std::size_t k = static_cast<std::size_t>(py) * n + static_cast<std::size_t>(px);
      if (std::isnan(z[k])) continue;
      double mx = 0, my = 0, m = 0;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const int qy = std::clamp(py + dy, 0, n - 1), qx = std::clamp(px + dx, 0, n - 1);
          const std::size_t q = static_cast<std::size_t>(qy) * n + static_cast<std::size_t>(qx);
          if (std::isnan(z[q])) continue;
          mx += gradient[q][0], my += gradient[q][1], ++m;
        }
      const double gx = gradient[k][0] - mx / m, gy = gradient[k][1] - my / m;
      detail[k] = (-gx + gy) / std::sqrt(2.0);  // light from the upper left (−x, +y)
      slope_scale = std::max(slope_scale, std::abs(detail[k]));
    }
  std::vector<unsigned char> rgb(z.size() * 3, 244);
  for (std::size_t k = 0; k < z.size(); ++k) {
    if (std::isnan(z[k])) continue;
    const Rgb base = sequential(high > low ? (z[k] - low) / (high - low) : 0.5);
    const double light = slope_scale > 0 ? 0.5 * detail[k] / slope_scale : 0.0;  // −0.5 … 0.5
    Rgb c;
    for (std::size_t i = 0; i < 3; ++i)
      c[i] = light >= 0 ? base[i] + (1 - base[i]) * light : base[i] * (1 + light);
    put_pixel(rgb, k, c);
  }
  return bmp_rgb_data_url(rgb, n);
}

// The kept turns of the path and its start and end, in the part image's pixel frame.
std::string path_overlay(const TurnSamples& t, double outer) {
  const int n = kPartPixels;
  const auto u = [&](double x) { return (x + outer) / (2 * outer) * n; };
  const auto v = [&](double y) { return (outer - y) / (2 * outer) * n; };
  std::string s = "<g fill=\"none\" stroke=\"#000\" stroke-opacity=\"0.55\" stroke-width=\"0.6\">";
  for (const auto& turn : t.turns) {
    if (turn.size() < 2) continue;
    std::string d;
    for (std::size_t i = 0; i < turn.size(); ++i) {
      d += i ? 'L' : 'M';
      d += fixed_text(u(turn[i].first), 1);
      d += ' ';
      d += fixed_text(v(turn[i].second), 1);
    }
    s += "<path d=\"" + d + "\"/>";
  }
  s += "</g>";
  if (t.any) {
    s += "<circle cx=\"" + fixed_text(u(t.start_x), 1) + "\" cy=\"" + fixed_text(v(t.start_y), 1) +
         "\" r=\"5\" fill=\"#1b7a1b\" stroke=\"#fff\" stroke-width=\"1.5\"><title>start</title></circle>";
    s += "<rect x=\"" + fixed_text(u(t.end_x) - 4.5, 1) + "\" y=\"" + fixed_text(v(t.end_y) - 4.5, 1) +
         "\" width=\"9\" height=\"9\" fill=\"#b00020\" stroke=\"#fff\" stroke-width=\"1.5\"><title>end</title></rect>";
  }
  return s;
}

// Index 0 is "no data" (light grey); 1…255 run from −limit (blue) to +limit (red).
std::string diverging_image(const ResidualHeatMap& m, double limit) {
  std::vector<unsigned char> palette(256 * 3, 244), index(m.mean.size(), 0);
  for (std::size_t k = 1; k < 256; ++k) put_pixel(palette, k, diverging((k - 1) / 254.0 * 2 - 1));
  for (std::size_t k = 0; k < m.mean.size(); ++k)
    if (!std::isnan(m.mean[k]))
      index[k] = static_cast<unsigned char>(
          1 + std::lround((std::clamp(m.mean[k] / limit, -1.0, 1.0) + 1) / 2 * 254));
  return bmp_indexed_data_url(index, palette, m.size);
}

std::string row(const std::string& key, const std::string& value) {
  return "<tr><th>" + html_escape(key) + "</th><td>" + value + "</td></tr>\n";
}

}  // namespace

std::string report_html(const RunReport& r, const Surface& design) {
  const PassFigures& f = r.passes.back();
  const JobParameters& p = r.parameters;
  const bool spiral = r.alpha_max_deg >= 0;
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width\"><title>" +
      html_escape(r.job) + " · freeturn report</title><style>"
      "body{font-family:system-ui,sans-serif;max-width:1240px;margin:1.5em auto;padding:0 1em;color:#222}"
      "h1{margin-bottom:.2em}h2{margin-top:1.6em;border-bottom:1px solid #ddd}"
      "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ddd;padding:3px 8px;vertical-align:top}"
      "th{text-align:left;background:#f6f6f6;font-weight:600}td.n{text-align:right;font-variant-numeric:tabular-nums}"
      ".verdict{font-size:1.3em;padding:.5em .8em;border-radius:4px;margin:.6em 0}"
      ".pass{background:#e3f4e3;color:#145214}.unsafe{background:#fbe3e6;color:#8a0015}"
      ".sev-unsafe{color:#8a0015;font-weight:600}.sev-warning{color:#8a4b00}.sev-note{color:#555}"
      ".grid2{display:flex;flex-wrap:wrap;gap:8px}figure{margin:6px}figcaption{font-size:.9em;color:#444;max-width:560px}"
      "svg text{font-size:11px;fill:#333}svg text.title{font-size:12px}svg .grid{stroke:#eee}svg .tick{stroke:#888}"
      "</style></head><body>\n";
  h += "<h1>" + html_escape(r.job) + "</h1>\n<p>" + html_escape(p.strategy) + " on " +
       html_escape(r.machine) + " · freeturn " + html_escape(r.version) + " · job file " +
       html_escape(r.job_file) + "</p>\n";

  // The verdict first, with its reasons.
  const std::vector<std::string> reasons = r.unsafe_reasons();
  if (reasons.empty()) {
    h += "<div id=\"verdict\" class=\"verdict pass\"><b>PASS</b>: every check passed and the "
         "program stays within the machine's limits.</div>\n";
  } else {
    h += "<div id=\"verdict\" class=\"verdict unsafe\"><b>UNSAFE</b>: do not cut this program as "
         "it is.<ul>";
    for (const std::string& u : reasons) h += "<li>" + html_escape(u) + "</li>";
    h += "</ul></div>\n";
  }

  // The summary.
  h += "<h2>Summary</h2><div class=\"grid2\"><table id=\"summary\">\n";
  h += row("cycle time", duration(f.cycle_time) + (f.scheduled ? " (block times scheduled to the machine's limits)" : ""));
  if (spiral && f.constant_rpm_cycle_time > 0)
    h += row("at one constant speed",
             duration(f.constant_rpm_cycle_time) + " at " + readable(f.dynamics.max_rpm, 2) + " rpm");
  if (spiral)
    h += row("spindle", readable(r.spindle_rpm, 2) + " rpm programmed, " +
                            readable(r.requested_rpm, 2) + " rpm requested");
  h += row("cutter points", std::to_string(f.points) + (spiral ? " over " + readable(f.revolutions, 1) + " revolutions" : ""));
  h += row("chord error", "max " + nm(f.chord_max) + ", RMS " + nm(f.chord_rms) +
                              (p.chord_tolerance > 0 ? " (tolerance " + nm(p.chord_tolerance) + ")" : ""));
  h += row("scallop", "max " + nm(f.scallop_max));
  if (f.held_points > 0)
    h += row("uncut at creases", "max " + nm(f.uncut_max) + " at θ = " +
                                     readable(part_degrees(f.uncut_theta), 3) + "°, r = " +
                                     readable(f.uncut_r, 4) + " mm (" + std::to_string(f.held_points) +
                                     " points hold the nose)");
  if (r.form_error) {
    const FormErrorSplit& e = *r.form_error;
    h += row("predicted figure", "PV " + nm(e.figure_pv) + ", RMS " + nm(e.figure_rms));
    h += row("predicted finish", "PV " + nm(e.finish_pv) + ", RMS " + nm(e.finish_rms) + " (the cusps)");
  }
  if (spiral) {
    const BaseFigures& b = r.base;
    h += row("base surface", html_escape(b.kind) + ", degree " + std::to_string(b.degree) + ", " +
                                 std::to_string(b.coefficients) + " coefficients; α<sub>max</sub> = " +
                                 readable(r.alpha_max_deg, 3) + "°");
    if (b.axis_searched)
      h += row("mount the part", "turning axis tilted " + readable(b.tilt_deg, 3) + "° (" +
                                     readable(b.tilt_x_deg, 3) + "° about x, " +
                                     readable(b.tilt_y_deg, 3) + "° about y), crossing the design at (" +
                                     readable(b.crossing_x, 4) + ", " + readable(b.crossing_y, 4) +
                                     ") mm: decentre the part by that much");
    else
      h += row("mount the part", "on its own axis (no axis search)");
  }
  h += "</table><table id=\"parameters\">\n";
  h += row("aperture", readable(p.inner_radius, 3) + " – " + readable(p.outer_radius, 3) + " mm radius");
  if (spiral) h += row("pitch", readable(p.pitch * 1e3, 3) + " µm a revolution, " + html_escape(p.direction));
  h += row("cutter points", html_escape(p.points_rule) +
                                (p.chord_tolerance > 0 ? ", chord tolerance " + nm(p.chord_tolerance) : "") +
                                (p.stand_off > 0 ? "; blocks stand off the design by " + nm(p.stand_off) : ""));
  h += row("tool", "nose radius " + readable(p.nose_radius, 4) + " mm, included angle " +
                       readable(p.included_angle_deg, 1) + "°, clearance " +
                       readable(p.clearance_angle_deg, 1) + "°");
  h += row("machine", html_escape(r.machine) + " (post " + html_escape(r.plugin) + ")");
  if (spiral) h += row("timing", html_escape(p.timing));
  else h += row("feed", readable(p.feed, 1) + " mm/min");
  if (!p.roughing_depths.empty()) {
    std::string depths;
    for (const double d : p.roughing_depths) depths += (depths.empty() ? "" : ", ") + readable(d * 1e3, 2) + " µm";
    h += row("roughing passes", depths);
  }
  h += "</table></div>\n";

  // The warnings, each where it happens.
  h += "<h2>Warnings</h2>\n";
  if (r.warnings.empty()) {
    h += "<p id=\"warnings\">None.</p>\n";
  } else {
    h += "<table id=\"warnings\"><tr><th>severity</th><th>what</th><th>pass</th><th>where</th>"
         "<th>value</th><th>limit</th><th>message</th></tr>\n";
    for (const ReportWarning& w : r.warnings) {
      std::string where;
      if (std::isfinite(w.theta_deg)) where += "θ = " + readable(w.theta_deg, 3) + "°";
      if (std::isfinite(w.r_mm)) where += (where.empty() ? "" : ", ") + std::string("r = ") + readable(w.r_mm, 4) + " mm";
      if (where.empty() && std::isfinite(w.x_mm))
        where = "(" + readable(w.x_mm, 4) + ", " + readable(w.y_mm, 4) + ") mm";
      const int decimals = w.unit == "nm" ? 1 : w.unit == "deg" ? 3 : w.unit == "rpm" ? 2 : 4;
      const std::string unit = w.unit == "deg" ? "°" : " " + w.unit;
      h += "<tr><td class=\"sev-" + std::string(to_string(w.severity)) + "\">" + to_string(w.severity) +
           "</td><td>" + html_escape(w.kind) + "</td><td>" + html_escape(w.pass) + "</td><td>" + where +
           "</td><td class=\"n\">" + (std::isfinite(w.value) ? readable(w.value, decimals) + unit : "") +
           "</td><td class=\"n\">" + (std::isfinite(w.limit) ? readable(w.limit, decimals) + unit : "") +
           "</td><td>" + html_escape(w.message) + "</td></tr>\n";
    }
    h += "</table>\n";
  }

  // The part and the path; the predicted form error.
  h += "<h2>The part and the predicted form error</h2><div class=\"grid2\">\n";
  const double outer = p.outer_radius;
  double low = 0, high = 0;
  const std::string part = part_image(design, p.inner_radius, outer, low, high);
  const long kept = static_cast<long>(f.turns.turns.size());
  h += map_figure("fig-part",
                  "The design's height (colour; shaded by its slope) and the finishing path, every " +
                      std::to_string(f.turns.turn_stride) + (f.turns.turn_stride == 1 ? "st" : "th") +
                      " turn (" + std::to_string(kept) + " drawn); ● start, ■ end",
                  part, kPartPixels, outer, spiral ? path_overlay(f.turns, outer) : "", sequential,
                  false, low * 1e3, high * 1e3, "µm", 1);
  if (r.figure_map && r.form_error) {
    const FormErrorSplit& e = *r.form_error;
    const double limit = std::max({std::abs(e.figure_max), std::abs(e.figure_min), 1e-9});
    h += map_figure("fig-form-error",
                    std::string("Predicted figure: the residual's mean over one pitch of radius, ") +
                        "piston (" + nm(e.piston) + ") removed; red above the design, blue below" +
                        (r.simulated ? "" : " (cut on the report's grid; simulate writes the residual itself)") +
                        (e.resolved ? "" : "; the grid is coarser than a third of the pitch"),
                    diverging_image(*r.figure_map, limit), r.figure_map->size, r.figure_map->half_width,
                    "", diverging, true, -limit * 1e6, limit * 1e6, "nm", 1);
  } else {
    h += "<p id=\"fig-form-error\">No form error map: it is made for spirals (a profile's "
         "section is the chord and scallop charts below).</p>";
  }
  h += "</div>\n";

  // Along the radius.
  h += "<h2>Along the radius</h2><div class=\"grid2\">\n";
  std::vector<ChartLine> marks;
  for (const ReportWarning& w : r.warnings)
    if (w.pass == f.name && std::isfinite(w.r_mm) && marks.size() < 8)
      marks.push_back({w.r_mm, w.kind, w.severity == ReportWarning::Severity::kUnsafe ? "#b00020" : "#a15c00"});
  {
    Chart c;
    c.id = "fig-chord";
    c.title = "Chord error of each block (every " + std::to_string(f.stride) + (f.stride == 1 ? "st" : "th") +
              " point; max " + nm(f.chord_max) + "), with the tolerance";
    c.x_title = "r (mm)";
    c.y_title = "chord error (nm)";
    c.y_from_zero = true;
    ChartSeries s{"", "#1f5fa8", {}, true};
    for (const PlotPoint& q : f.samples) s.points.emplace_back(q.r, q.chord * 1e6);
    c.series.push_back(std::move(s));
    if (p.chord_tolerance > 0) c.horizontal.push_back({p.chord_tolerance * 1e6, "tolerance " + nm(p.chord_tolerance), "#b00020"});
    c.vertical = marks;
    h += svg_chart(c);
  }
  {
    Chart c;
    c.id = "fig-finish";
    c.title = "Finish and material left: the scallop of each point, the uncut residual at creases"
              " (max per band)" + std::string(r.form_error ? " and the predicted finish PV per band" : "");
    c.x_title = "r (mm)";
    c.y_title = "height above the design (nm)";
    c.y_from_zero = true;
    ChartSeries s{"scallop", "#1f5fa8", {}, true};
    for (const PlotPoint& q : f.samples) s.points.emplace_back(q.r, q.scallop * 1e6);
    c.series.push_back(std::move(s));
    if (!f.uncut_by_band.empty()) {
      ChartSeries u{"uncut residual", "#b00020", {}, false};
      for (std::size_t k = 0; k < f.uncut_by_band.size(); ++k)
        u.points.emplace_back((k + 0.5) * f.band_width, f.uncut_by_band[k] * 1e6);
      c.series.push_back(std::move(u));
    }
    if (r.form_error) {
      const FormErrorSplit& e = *r.form_error;
      ChartSeries fin{"predicted finish PV", "#2a8a2a", {}, false};
      for (std::size_t k = 0; k < e.finish_pv_by_band.size(); ++k)
        fin.points.emplace_back(e.band_inner + (k + 0.5) * e.band_width, e.finish_pv_by_band[k] * 1e6);
      c.series.push_back(std::move(fin));
    }
    h += svg_chart(c);
  }
  const auto axis_chart = [&](int axis, bool acceleration) {
    const bool angular = axis >= 2;
    const std::string unit = angular ? (acceleration ? "°/s²" : "°/s") : (acceleration ? "mm/s²" : "mm/s");
    Chart c;
    c.id = std::string(acceleration ? "fig-acceleration-" : "fig-velocity-") + kAxes[axis];
    c.title =
        std::string(kAxes[axis]) + (acceleration ? " acceleration" : " velocity") +
        (f.cubic_blocks ? " on the controller's cubics (the largest in each block), every "
                        : " of the blocks as written, every ") +
        std::to_string(f.block_stride) + (f.block_stride == 1 ? "st" : "th") +
        ", with the machine's limits (peak " +
        readable(acceleration ? f.dynamics.peak_acceleration[axis] : f.dynamics.peak_velocity[axis],
                 2) +
        " " + unit + ")";
    c.x_title = "programmed radius |X| (mm)";
    c.y_title = std::string(kAxes[axis]) + (acceleration ? " acceleration (" : " velocity (") + unit + ")";
    c.y_from_zero = true;
    ChartSeries s{"", "#1f5fa8", {}, true};
    for (const BlockPoint& q : f.blocks) s.points.emplace_back(q.r, acceleration ? q.a[axis] : q.v[axis]);
    c.series.push_back(std::move(s));
    const double limit = acceleration ? r.max_acceleration[axis] : r.max_velocity[axis];
    if (std::isfinite(limit) && limit > 0) {
      c.horizontal.push_back({limit, "limit " + readable(limit, 1) + " " + unit, "#b00020"});
      c.horizontal.push_back({-limit, "limit −" + readable(limit, 1) + " " + unit, "#b00020"});
    }
    c.vertical = marks;
    return svg_chart(c);
  };
  h += axis_chart(0, false);
  h += axis_chart(1, false);
  if (spiral) h += axis_chart(2, false);
  h += axis_chart(0, true);
  h += axis_chart(1, true);
  if (spiral) {
    Chart c;
    c.id = "fig-points-per-revolution";
    c.title = "Cutter points per revolution";
    c.x_title = "revolution";
    c.y_title = "points";
    c.y_from_zero = true;
    ChartSeries s{"", "#1f5fa8", {}, false};
    for (std::size_t k = 0; k < f.points_per_revolution.size(); ++k)
      s.points.emplace_back(static_cast<double>(k), static_cast<double>(f.points_per_revolution[k]));
    c.series.push_back(std::move(s));
    h += svg_chart(c);
  }
  h += "</div>\n";

  // The metrology loop: each measured part, its registration, the error fitted and the
  // correction cut.
  if (!r.compensation.empty()) {
    h += "<h2>Compensation</h2>\n<p>The job cuts the design less gain × the error each measured "
         "part showed (docs/metrology.md).</p><table id=\"compensation\"><tr><th>measured part</th>"
         "<th>points used</th><th>registration (decentre, tilt, clocking, piston)</th>"
         "<th>measured error</th><th>fit residual</th><th>gain</th><th>correction</th>"
         "<th>predicted after</th></tr>\n";
    for (const MeasuredPart& m : r.compensation) {
      const Registration& g = m.registration;
      h += "<tr><td>" + html_escape(m.file) + " (" + html_escape(m.format) + ")</td><td class=\"n\">" +
           std::to_string(g.used) + " of " + std::to_string(m.points + m.invalid) + " (" +
           std::to_string(m.invalid) + " invalid, " + std::to_string(g.outliers) + " outliers)</td><td>(" +
           readable(g.decentre_x * 1e3, 2) + ", " + readable(g.decentre_y * 1e3, 2) + ") µm, (" +
           readable(g.tilt_x * 1e6, 2) + ", " + readable(g.tilt_y * 1e6, 2) + ") µrad, " +
           readable(g.clocking * kDegrees, 4) + "°, " + readable(g.piston * 1e3, 3) + " µm</td><td class=\"n\">RMS " +
           nm(g.measured_rms) + ", PV " + nm(g.measured_pv) + "</td><td class=\"n\">" + nm(g.fit_rms) +
           " RMS</td><td class=\"n\">" + readable(m.gain, 2) + "</td><td class=\"n\">" +
           nm(m.gain * fitted_error_rms(m)) + " RMS</td><td class=\"n\">" + nm(compensated_rms(m)) +
           " RMS</td></tr>\n";
    }
    h += "</table><div class=\"grid2\">\n";
    for (std::size_t k = 0; k < r.compensation.size(); ++k) {
      const MeasuredPart& m = r.compensation[k];
      const Zernike error(0, 0, {}, m.registration.normalization_radius, m.registration.zernike);
      ResidualHeatMap map;
      map.size = kMapPixels;
      map.half_width = outer;
      map.mean.assign(static_cast<std::size_t>(kMapPixels) * kMapPixels, std::nan(""));
      double limit = 1e-12;
      for (int py = 0; py < kMapPixels; ++py)
        for (int px = 0; px < kMapPixels; ++px) {
          const double x = -outer + (px + 0.5) * 2 * outer / kMapPixels;
          const double y = outer - (py + 0.5) * 2 * outer / kMapPixels;
          const double rad = std::hypot(x, y);
          if (rad > outer || rad < p.inner_radius) continue;
          const double b = m.registration.bspline
                               ? bspline_height(*m.registration.bspline,
                                                m.registration.normalization_radius, x, y)
                               : 0.0;
          const double e = m.gain * (error.sag(x, y) + b);
          map.mean[static_cast<std::size_t>(py) * kMapPixels + static_cast<std::size_t>(px)] = e;
          limit = std::max(limit, std::abs(e));
        }
      h += map_figure("fig-correction-" + std::to_string(k + 1),
                      "The correction cut for " + m.file + ": gain × the fitted error (" +
                          std::to_string(m.registration.zernike.size()) + " Zernike terms" +
                          (m.registration.bspline ? " and a B-spline" : "") +
                          "), subtracted from the design",
                      diverging_image(map, limit), kMapPixels, outer, "", diverging, true,
                      -limit * 1e6, limit * 1e6, "nm", 1);
    }
    h += "</div>\n";
  }

  // The passes and, when simulated, the worst places.
  h += "<h2>Passes</h2><table id=\"passes\"><tr><th>pass</th><th>stock</th><th>points</th>"
       "<th>chord max</th><th>scallop max</th><th>uncut max</th><th>cycle</th></tr>\n";
  for (const PassFigures& q : r.passes)
    h += "<tr><th>" + html_escape(q.name) + "</th><td class=\"n\">" + readable(q.stock * 1e3, 2) +
         " µm</td><td class=\"n\">" + std::to_string(q.points) + "</td><td class=\"n\">" + nm(q.chord_max) +
         "</td><td class=\"n\">" + nm(q.scallop_max) + "</td><td class=\"n\">" + nm(q.uncut_max) +
         "</td><td class=\"n\">" + duration(q.cycle_time) + "</td></tr>\n";
  h += "</table>\n";
  if (r.simulation) {
    const SimulationResult& s = *r.simulation;
    const double ratio = s.pv > 0 ? s.predicted.pv() / s.pv : 0;
    h += "<h2>Simulated cut</h2>\n<p id=\"simulation\">" +
         std::string(r.simulated ? "The finishing pass cut in simulation" : "The finishing pass cut on the report's grid") +
         " (" + std::to_string(s.rings) + " radii × " + std::to_string(s.columns) +
         " angles): residual PV " + nm(s.pv) + ", RMS " + nm(s.rms) + ". The planner predicted PV " +
         nm(s.predicted.pv()) + ", " + readable(ratio, 3) + "× the simulation: " +
         prediction_bound_text(ratio) + ".</p>\n";
    h += "<table id=\"worst\"><tr><th>worst place</th><th>r</th><th>θ</th><th>residual</th><th>cause</th></tr>\n";
    for (std::size_t k = 0; k < s.worst.size(); ++k) {
      std::string cause = to_string(s.worst[k].cause);
      std::replace(cause.begin(), cause.end(), '_', ' ');
      h += "<tr><th>" + std::to_string(k + 1) + "</th><td class=\"n\">" + readable(s.worst[k].r, 4) +
           " mm</td><td class=\"n\">" + readable(s.worst[k].phi * kDegrees, 3) + "°</td><td class=\"n\">" +
           nm(s.worst[k].residual) + "</td><td>" + cause + "</td></tr>\n";
    }
    h += "</table>\n";
  }
  h += "<h2>The job</h2><pre id=\"job-yaml\">" + html_escape(r.job_text) + "</pre>\n";
  h += "</body></html>\n";
  return h;
}

}  // namespace freeturn::detail
