#include "common/svg.h"

#include "common/output_file.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace plateball::tools {
namespace {

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string StyleAttr(const SvgFigure::Style& s) {
  std::ostringstream os;
  os << "stroke=\"" << s.stroke << "\" stroke-width=\"" << s.width << "\" fill=\"" << s.fill << "\"";
  if (!s.dash.empty()) os << " stroke-dasharray=\"" << s.dash << "\"";
  return os.str();
}

}  // namespace

void SvgFigure::Polyline(const std::vector<Eigen::Vector2d>& points, const Style& style) {
  items_.push_back({0, points, style, 0, ""});
}
void SvgFigure::Marker(const Eigen::Vector2d& p, double radius_px, const Style& style) {
  items_.push_back({1, {p}, style, radius_px, ""});
}
void SvgFigure::Text(const Eigen::Vector2d& p, const std::string& text, double size_px, const std::string& color) {
  Style s;
  s.stroke = color;
  items_.push_back({2, {p}, s, size_px, text});
}
void SvgFigure::Legend(const std::string& text, const Style& style) { legend_.emplace_back(text, style); }

std::string SvgFigure::Render() const {
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const Item& it : items_)
    for (const auto& p : it.points)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.allFinite() && hi.allFinite())) lo = {-1, -1}, hi = {1, 1};
  Eigen::Vector2d span = (hi - lo).cwiseMax(1e-9);
  lo -= 0.06 * span;
  hi += 0.06 * span;
  span = hi - lo;
  const double margin = 40, top = title_.empty() ? 20 : 50;
  const double w = width_ - 2 * margin;
  double h = height_ - margin - top;
  double sx = w / span.x(), sy = h / span.y();
  if (equal_aspect_) sx = sy = std::min(sx, sy);
  // A wide drawing at 1:1 leaves the canvas's lower part empty: the canvas ends below the drawing.
  if (equal_aspect_) h = span.y() * sy;
  const double height = top + h + margin;
  const double ox = 0.5 * (w - span.x() * sx), oy = 0.5 * (h - span.y() * sy);  // centre the drawing
  auto map = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(margin + ox + (p.x() - lo.x()) * sx, top + h - oy - (p.y() - lo.y()) * sy);
  };
  std::ostringstream os;
  os.precision(6);
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_ << "\" height=\"" << height
     << "\" viewBox=\"0 0 " << width_ << " " << height << "\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!title_.empty())
    os << "<text x=\"" << width_ / 2 << "\" y=\"28\" font-family=\"sans-serif\" font-size=\"16\" text-anchor=\"middle\">"
       << Escape(title_) << "</text>\n";
  for (const Item& it : items_) {
    if (it.kind == 0) {
      os << "<polyline " << StyleAttr(it.style) << " stroke-linejoin=\"round\" points=\"";
      for (const auto& p : it.points) {
        const Eigen::Vector2d q = map(p);
        os << q.x() << "," << q.y() << " ";
      }
      os << "\"/>\n";
    } else if (it.kind == 1) {
      const Eigen::Vector2d q = map(it.points[0]);
      os << "<circle cx=\"" << q.x() << "\" cy=\"" << q.y() << "\" r=\"" << it.size << "\" " << StyleAttr(it.style)
         << "/>\n";
    } else {
      const Eigen::Vector2d q = map(it.points[0]);
      os << "<text x=\"" << q.x() << "\" y=\"" << q.y() << "\" font-family=\"sans-serif\" font-size=\"" << it.size
         << "\" fill=\"" << it.style.stroke << "\">" << Escape(it.text) << "</text>\n";
    }
  }
  double y = top + 14;
  for (const auto& [text, style] : legend_) {
    os << "<line x1=\"" << margin + 8 << "\" y1=\"" << y - 4 << "\" x2=\"" << margin + 38 << "\" y2=\"" << y - 4
       << "\" " << StyleAttr(style) << "/>\n";
    os << "<text x=\"" << margin + 46 << "\" y=\"" << y << "\" font-family=\"sans-serif\" font-size=\"12\">"
       << Escape(text) << "</text>\n";
    y += 18;
  }
  os << "</svg>\n";
  return os.str();
}

void SvgFigure::Write(const std::string& path) const { WriteOutput(path, Render()); }

std::string RenderLogLogChart(const std::string& title, const std::string& x_label, const std::string& y_label,
                              const std::vector<LogLogSeries>& series, double width_px, double height_px) {
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const auto& s : series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        xlo = std::min(xlo, std::log10(s.x[i]));
        xhi = std::max(xhi, std::log10(s.x[i]));
        ylo = std::min(ylo, std::log10(s.y[i]));
        yhi = std::max(yhi, std::log10(s.y[i]));
      }
  if (!(std::isfinite(xlo) && std::isfinite(ylo))) xlo = ylo = 0, xhi = yhi = 1;
  xlo = std::floor(xlo * 10) / 10 - 0.05;
  xhi = std::ceil(xhi * 10) / 10 + 0.05;
  ylo = std::floor(ylo) - 0.0;
  yhi = std::ceil(yhi) + 0.0;
  if (xhi - xlo < 0.2) xlo -= 0.1, xhi += 0.1;
  if (yhi - ylo < 1) yhi += 1;
  const double left = 80, right = 30, top = 50, bottom = 60;
  const double w = width_px - left - right, h = height_px - top - bottom;
  auto X = [&](double lx) { return left + (lx - xlo) / (xhi - xlo) * w; };
  auto Y = [&](double ly) { return top + h - (ly - ylo) / (yhi - ylo) * h; };
  std::ostringstream os;
  os.precision(6);
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\"" << height_px
     << "\" viewBox=\"0 0 " << width_px << " " << height_px << "\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  os << "<text x=\"" << width_px / 2 << "\" y=\"28\" font-family=\"sans-serif\" font-size=\"16\" text-anchor=\"middle\">"
     << Escape(title) << "</text>\n";
  os << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w << "\" height=\"" << h
     << "\" fill=\"none\" stroke=\"black\"/>\n";
  for (int d = static_cast<int>(ylo); d <= static_cast<int>(yhi); ++d) {
    os << "<line x1=\"" << left << "\" y1=\"" << Y(d) << "\" x2=\"" << left + w << "\" y2=\"" << Y(d)
       << "\" stroke=\"#ddd\"/>\n";
    os << "<text x=\"" << left - 8 << "\" y=\"" << Y(d) + 4
       << "\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"end\">1e" << d << "</text>\n";
  }
  // x ticks at the data's x values of the first series (partition sizes), else decades.
  std::vector<double> ticks;
  if (!series.empty())
    for (double x : series.front().x)
      if (x > 0) ticks.push_back(x);
  for (double x : ticks) {
    const double lx = std::log10(x);
    os << "<line x1=\"" << X(lx) << "\" y1=\"" << top << "\" x2=\"" << X(lx) << "\" y2=\"" << top + h
       << "\" stroke=\"#eee\"/>\n";
    os << "<text x=\"" << X(lx) << "\" y=\"" << top + h + 18
       << "\" font-family=\"sans-serif\" font-size=\"12\" text-anchor=\"middle\">" << x << "</text>\n";
  }
  os << "<text x=\"" << left + w / 2 << "\" y=\"" << height_px - 18
     << "\" font-family=\"sans-serif\" font-size=\"13\" text-anchor=\"middle\">" << Escape(x_label) << "</text>\n";
  os << "<text x=\"18\" y=\"" << top + h / 2 << "\" font-family=\"sans-serif\" font-size=\"13\" text-anchor=\"middle\""
     << " transform=\"rotate(-90 18 " << top + h / 2 << ")\">" << Escape(y_label) << "</text>\n";
  double ly = top + 18;
  for (const auto& s : series) {
    os << "<polyline " << StyleAttr(s.style) << " points=\"";
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) os << X(std::log10(s.x[i])) << "," << Y(std::log10(s.y[i])) << " ";
    os << "\"/>\n";
    if (s.markers)
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
        if (s.x[i] > 0 && s.y[i] > 0)
          os << "<circle cx=\"" << X(std::log10(s.x[i])) << "\" cy=\"" << Y(std::log10(s.y[i])) << "\" r=\"3.5\" fill=\""
             << s.style.stroke << "\"/>\n";
    os << "<line x1=\"" << left + w - 250 << "\" y1=\"" << ly - 4 << "\" x2=\"" << left + w - 220 << "\" y2=\"" << ly - 4
       << "\" " << StyleAttr(s.style) << "/>\n";
    os << "<text x=\"" << left + w - 212 << "\" y=\"" << ly << "\" font-family=\"sans-serif\" font-size=\"12\">"
       << Escape(s.label) << "</text>\n";
    ly += 18;
  }
  os << "</svg>\n";
  return os.str();
}

}  // namespace plateball::tools
