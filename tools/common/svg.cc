#include "common/svg.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/invalid_input.h"
#include "common/output_file.h"

namespace plateball::tools {

struct LegendItem {
  std::string text;
  SvgFigure::Style style;
  SvgFigure::Swatch swatch;
  bool with_point;
};

namespace {

FigureSize g_figure_size;  // set once from the command line (AddFigureSizeOption)

constexpr double kFont = 12;       // tick labels, legend
constexpr double kLegendRow = 20;  // pixels per legend row
constexpr double kArrowPx = 26;    // length of a start/goal direction arrow

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    // C0 controls other than tab, line feed and carriage return are not XML 1.0 characters (not
    // even as references): each is shown as U+FFFD, the replacement character.
    else if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
      out += "\xEF\xBF\xBD";
    else
      out += c;
  }
  return out;
}

std::string StyleAttr(const SvgFigure::Style& s) {
  std::ostringstream os;
  os << "stroke=\"" << s.stroke << "\" stroke-width=\"" << s.width << "\" fill=\"" << s.fill << "\"";
  if (!s.dash.empty()) os << " stroke-dasharray=\"" << s.dash << "\"";
  return os.str();
}

// Width of a text in pixels (sans-serif, ~0.56 em per character; UTF-8 continuation bytes skipped).
double TextWidth(const std::string& text, double size) {
  std::size_t chars = 0;
  for (unsigned char c : text)
    if ((c & 0xC0) != 0x80) ++chars;
  return 0.56 * size * static_cast<double>(chars);
}

std::string TextTag(double x,
                    double y,
                    double size,
                    const std::string& anchor,
                    const std::string& text,
                    const std::string& extra = "") {
  std::ostringstream os;
  os.precision(6);
  os << "<text x=\"" << x << "\" y=\"" << y << "\" font-family=\"sans-serif\" font-size=\"" << size
     << "\" text-anchor=\"" << anchor << "\"" << extra << ">" << Escape(text) << "</text>\n";
  return os.str();
}

// A step of 1, 2 or 5 times a power of ten giving about `count` ticks over `span`.
double NiceStep(double span, double count) {
  const double raw = span / std::max(count, 1.0);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  return (norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0) * mag;
}

std::string TickText(double v, double step) {
  if (std::abs(v) < 1e-9 * step) v = 0.0;  // no "-0" or "1e-17"
  std::ostringstream os;
  os.precision(std::abs(v) >= 1e5 || (step < 1e-3 && v != 0.0) ? 3 : 10);
  os << v;
  return os.str();
}

// The title broken at ", ", "; " or ": " into lines that fit `max_px`.
std::vector<std::string> WrapTitle(const std::string& title, double max_px, double size) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&]() {
    if (!line.empty() && TextWidth(line + word, size) > max_px) lines.push_back(line), line.clear();
    line += word;
    word.clear();
  };
  for (std::size_t i = 0; i < title.size(); ++i) {
    word += title[i];
    if (i + 1 < title.size() && title[i + 1] == ' ' && (title[i] == ',' || title[i] == ';' || title[i] == ':')) {
      word += ' ';
      ++i;
      flush_word();
    }
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// An arrow from `from` (pixels) along the unit pixel direction `u`.
std::string Arrow(const Eigen::Vector2d& from, const Eigen::Vector2d& u, const std::string& colour, double length) {
  const Eigen::Vector2d tip = from + length * u, n(-u.y(), u.x());
  const Eigen::Vector2d a = tip - 7 * u + 3.5 * n, b = tip - 7 * u - 3.5 * n;
  std::ostringstream os;
  os.precision(6);
  os << "<line x1=\"" << from.x() << "\" y1=\"" << from.y() << "\" x2=\"" << (tip - 5 * u).x() << "\" y2=\""
     << (tip - 5 * u).y() << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n";
  os << "<polygon points=\"" << tip.x() << "," << tip.y() << " " << a.x() << "," << a.y() << " " << b.x() << ","
     << b.y() << "\" fill=\"" << colour << "\"/>\n";
  return os.str();
}

const char* const kStartColour = "#1a9850";

// The start (filled disc) or goal (ring) symbol at pixel q, with its arrow when u is non-zero.
std::string EndSymbol(bool start, const Eigen::Vector2d& q, const Eigen::Vector2d& u, double arrow_length) {
  std::ostringstream os;
  os.precision(6);
  const std::string colour = start ? kStartColour : "black";
  // The goal's arrow ends at its ring (radius 6 + 2) so that the head stays visible.
  if (u.norm() > 0) os << Arrow(start ? q : Eigen::Vector2d(q - (arrow_length + 8) * u), u, colour, arrow_length);
  if (start)
    os << "<circle cx=\"" << q.x() << "\" cy=\"" << q.y() << "\" r=\"5\" fill=\"" << colour
       << "\" stroke=\"white\" stroke-width=\"1\"/>\n";
  else
    os << "<circle cx=\"" << q.x() << "\" cy=\"" << q.y() << "\" r=\"6\" fill=\"white\" fill-opacity=\"0.6\" "
       << "stroke=\"black\" stroke-width=\"2\"/>\n";
  return os.str();
}

// A legend swatch 30 px wide whose left end is at (x, y) (y: the text's middle).
std::string Swatch(SvgFigure::Swatch kind, const SvgFigure::Style& style, bool with_point, double x, double y) {
  std::ostringstream os;
  os.precision(6);
  if (kind == SvgFigure::Swatch::kAuto)
    kind = style.fill != "none" ? SvgFigure::Swatch::kPoint : SvgFigure::Swatch::kLine;
  if (kind == SvgFigure::Swatch::kLine || with_point)
    os << "<line x1=\"" << x << "\" y1=\"" << y << "\" x2=\"" << x + 30 << "\" y2=\"" << y << "\" " << StyleAttr(style)
       << "/>\n";
  if (kind == SvgFigure::Swatch::kPoint || with_point)
    os << "<circle cx=\"" << x + 15 << "\" cy=\"" << y << "\" r=\"3.2\" fill=\""
       << (style.fill != "none" ? style.fill : style.stroke) << "\" stroke=\"" << style.stroke << "\"/>\n";
  if (kind == SvgFigure::Swatch::kStart || kind == SvgFigure::Swatch::kGoal) {
    const bool start = kind == SvgFigure::Swatch::kStart;
    os << EndSymbol(start, Eigen::Vector2d(x + (start ? 6 : 26), y), Eigen::Vector2d(1, 0), 20);
  }
  return os.str();
}

// Legend entries flowed into rows under the plot, from `top`, between `left` and `right`.
// Returns the SVG and sets *height to the rows' height.
std::string LegendRows(const std::vector<LegendItem>& items, double left, double right, double top, double* height) {
  std::ostringstream os;
  double x = left, y = top + kLegendRow / 2;
  for (const LegendItem& it : items) {
    const double w = 38 + TextWidth(it.text, kFont) + 18;
    if (x > left && x + w > right) x = left, y += kLegendRow;
    os << Swatch(it.swatch, it.style, it.with_point, x, y) << TextTag(x + 38, y + 4, kFont, "start", it.text);
    x += w;
  }
  *height = items.empty() ? 0.0 : y + kLegendRow / 2 - top;
  return os.str();
}

std::string SvgOpen(double width, double height) {
  std::ostringstream os;
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 "
     << width << " " << height << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  return os.str();
}

std::string TitleLines(const std::vector<std::string>& lines, double width) {
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) out += TextTag(width / 2, 24 + 20.0 * i, 15, "middle", lines[i]);
  return out;
}

// The axis labels: x centred under the plot box, y rotated left of it.
std::string AxisLabelTags(
    const std::string& x_label, const std::string& y_label, double left, double top, double w, double h) {
  std::ostringstream os;
  os.precision(6);
  os << TextTag(left + w / 2, top + h + 38, 13, "middle", x_label);
  os << "<text x=\"16\" y=\"" << top + h / 2 << "\" font-family=\"sans-serif\" font-size=\"13\" text-anchor=\"middle\""
     << " transform=\"rotate(-90 16 " << top + h / 2 << ")\">" << Escape(y_label) << "</text>\n";
  return os.str();
}

// Linear ticks of [lo, hi] with `step`, mapped by `map` (grid lines across the plot box).
std::string LinearTicks(bool x_axis,
                        double lo,
                        double hi,
                        double step,
                        double left,
                        double top,
                        double w,
                        double h,
                        const std::function<double(double)>& map) {
  std::ostringstream os;
  os.precision(6);
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
    const double p = map(v);
    if (x_axis) {
      os << "<line x1=\"" << p << "\" y1=\"" << top << "\" x2=\"" << p << "\" y2=\"" << top + h
         << "\" stroke=\"#e4e4e4\"/>\n<line x1=\"" << p << "\" y1=\"" << top + h << "\" x2=\"" << p << "\" y2=\""
         << top + h + 5 << "\" stroke=\"black\"/>\n";
      os << TextTag(p, top + h + 18, kFont, "middle", TickText(v, step));
    } else {
      os << "<line x1=\"" << left << "\" y1=\"" << p << "\" x2=\"" << left + w << "\" y2=\"" << p
         << "\" stroke=\"#e4e4e4\"/>\n<line x1=\"" << left - 5 << "\" y1=\"" << p << "\" x2=\"" << left << "\" y2=\""
         << p << "\" stroke=\"black\"/>\n";
      os << TextTag(left - 8, p + 4, kFont, "end", TickText(v, step));
    }
  }
  return os.str();
}

}  // namespace

FigureSize ParseFigureSize(const std::string& option, const std::string& text) {
  const std::size_t x = text.find_first_of("xX");
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos) return -1.0;
    return std::stod(part);
  };
  const double w = x == std::string::npos ? -1.0 : number(text.substr(0, x));
  const double h = x == std::string::npos ? -1.0 : number(text.substr(x + 1));
  if (!(w >= 200 && w <= 8000 && h >= 200 && h <= 8000)) {
    const std::string shown = text.size() > 40 ? text.substr(0, 40) + "..." : text;
    ThrowInvalidInput(CommandLineField(option),
                      "\"" + shown + "\"",
                      "must be WIDTHxHEIGHT in pixels, each an integer in [200, 8000]");
  }
  return {w, h};
}

void AddFigureSizeOption(CLI::App& app) {
  app.add_option_function<std::string>(
         "--figure-size",
         [](const std::string& text) {
           try {
             SetFigureSize(ParseFigureSize("--figure-size", text));
           } catch (const std::invalid_argument& e) {
             throw CLI::ValidationError(e.what());
           }
         },
         "size of the SVG figures in pixels, WIDTHxHEIGHT, e.g. 800x600 (default: 640 wide, height fitted; charts "
         "720x520)")
      ->type_name("WxH");
}

FigureSize CurrentFigureSize() { return g_figure_size; }
void SetFigureSize(const FigureSize& size) { g_figure_size = size; }

SvgFigure::SvgFigure() : width_(g_figure_size.width > 0 ? g_figure_size.width : 640), height_(g_figure_size.height) {}

void SvgFigure::Polyline(const std::vector<Eigen::Vector2d>& points, const Style& style) {
  items_.push_back({Kind::kPolyline, points, style, 0, ""});
}
void SvgFigure::Marker(const Eigen::Vector2d& p, double radius_px, const Style& style) {
  items_.push_back({Kind::kMarker, {p}, style, radius_px, ""});
}
void SvgFigure::Text(const Eigen::Vector2d& p, const std::string& text, double size_px, const std::string& color) {
  Style s;
  s.stroke = color;
  items_.push_back({Kind::kText, {p}, s, size_px, text});
}
void SvgFigure::AddEnd(Kind kind,
                       const Eigen::Vector2d& p,
                       const Eigen::Vector2d& direction,
                       const std::string& label) {
  const Eigen::Vector2d d = direction.allFinite() ? direction : Eigen::Vector2d::Zero();
  items_.push_back({kind, {p, d}, Style{}, 13, label});
  const bool start = kind == Kind::kStart;
  const std::string entry = start ? "start (arrow: direction of motion)" : "goal (arrow: direction of arrival)";
  for (const LegendEntry& e : legend_)
    if (e.text == entry) return;
  // Start and goal lead the legend, start first.
  const auto at = start ? legend_.begin() : std::find_if(legend_.begin(), legend_.end(), [](const LegendEntry& e) {
    return e.swatch != Swatch::kStart;
  });
  legend_.insert(at, {entry, Style{}, start ? Swatch::kStart : Swatch::kGoal});
}
void SvgFigure::Start(const Eigen::Vector2d& p, const Eigen::Vector2d& direction, const std::string& label) {
  AddEnd(Kind::kStart, p, direction, label);
}
void SvgFigure::Goal(const Eigen::Vector2d& p, const Eigen::Vector2d& direction, const std::string& label) {
  AddEnd(Kind::kGoal, p, direction, label);
}
void SvgFigure::Legend(const std::string& text, const Style& style, Swatch swatch) {
  legend_.push_back({text, style, swatch});
}

// The plot box in pixels and the world box it shows.
struct SvgFigure::Frame {
  Eigen::Vector2d lo, hi;
  double sx = 1, sy = 1, left = 70, right = 24, top = 0, w = 0, h = 0, height = 0, legend_h = 0;
  std::vector<std::string> title;
  Eigen::Vector2d Map(const Eigen::Vector2d& p) const {
    return {left + (p.x() - lo.x()) * sx, top + h - (p.y() - lo.y()) * sy};
  }
};

SvgFigure::Frame SvgFigure::Layout(const std::vector<LegendItem>& legend) const {
  Frame f;
  // World box of everything drawn, padded so that markers and arrows stay inside the plot.
  f.lo = Eigen::Vector2d(INFINITY, INFINITY), f.hi = -f.lo;
  for (const Item& it : items_)
    for (std::size_t i = 0; i < (it.kind == Kind::kStart || it.kind == Kind::kGoal ? 1 : it.points.size()); ++i)
      if (it.points[i].allFinite()) f.lo = f.lo.cwiseMin(it.points[i]), f.hi = f.hi.cwiseMax(it.points[i]);
  if (!(f.lo.allFinite() && f.hi.allFinite())) f.lo = {-1, -1}, f.hi = {1, 1};
  Eigen::Vector2d span = (f.hi - f.lo).cwiseMax(1e-9 * std::max(1.0, (f.hi - f.lo).maxCoeff()));
  const double pad = axes_ ? 0.08 : 0.06;
  f.lo -= pad * span;
  f.hi += pad * span;
  span = f.hi - f.lo;
  if (!axes_) {  // the caller's own chart: the box fills the canvas less the margins
    if (!title_.empty()) f.title = {title_};
    f.left = f.right = 40;
    f.top = title_.empty() ? 20 : 50;
    f.w = width_ - 80;
    f.h = (height_ > 0 ? height_ : 0.75 * width_) - 40 - f.top;
    f.sx = f.w / span.x(), f.sy = f.h / span.y();
    if (equal_aspect_) f.sx = f.sy = std::min(f.sx, f.sy);
    f.height = f.top + f.h + 40;
    return f;
  }
  // Title lines, plot box, tick labels and axis labels, legend rows.
  if (!title_.empty()) f.title = WrapTitle(title_, width_ - 20, 15);
  f.top = 16 + 20.0 * static_cast<double>(f.title.size());
  f.w = width_ - f.left - f.right;
  LegendRows(legend, f.left, width_ - f.right, 0, &f.legend_h);
  const double below = 50 + f.legend_h + 8;
  f.h = height_ > 0 ? height_ - f.top - below : 0.0;
  if (f.h <= 0) f.h = equal_aspect_ ? std::clamp(f.w * span.y() / span.x(), 0.4 * f.w, 1.3 * f.w) : 0.7 * f.w;
  f.h = std::max(f.h, 60.0);
  f.sx = f.w / span.x(), f.sy = f.h / span.y();
  if (equal_aspect_) {  // one scale: the world box grows along the axis with room to spare
    f.sx = f.sy = std::min(f.sx, f.sy);
    const Eigen::Vector2d mid = 0.5 * (f.lo + f.hi), half(0.5 * f.w / f.sx, 0.5 * f.h / f.sy);
    f.lo = mid - half, f.hi = mid + half;
  }
  f.height = height_ > 0 ? height_ : f.top + f.h + below;
  return f;
}

// The unit pixel direction of a start/goal item's arrow (zero: none).
Eigen::Vector2d SvgFigure::ArrowDirection(const Item& it, const Frame& f) const {
  const Eigen::Vector2d d(it.points[1].x() * f.sx, -it.points[1].y() * f.sy);
  return d.norm() > 0 ? Eigen::Vector2d(d / d.norm()) : Eigen::Vector2d::Zero();
}

// A start or goal symbol with its label beside the arrow: the start's on the arrow's upper side,
// the goal's on its lower side, or opposite the start's when the two coincide (a closed path).
std::string SvgFigure::EndItem(const Item& it, const Frame& f) const {
  const bool start = it.kind == Kind::kStart;
  const Eigen::Vector2d q = f.Map(it.points[0]), u = ArrowDirection(it, f);
  auto normal = [](const Eigen::Vector2d& dir, bool upper) {
    Eigen::Vector2d n = dir.norm() > 0 ? Eigen::Vector2d(-dir.y(), dir.x()) : Eigen::Vector2d(0.6, -0.8);
    return (n.y() > 0) == upper ? Eigen::Vector2d(-n) : n;
  };
  Eigen::Vector2d n = normal(u, start);
  if (!start)
    for (const Item& other : items_)
      if (other.kind == Kind::kStart && (f.Map(other.points[0]) - q).norm() < 20)
        n = -normal(ArrowDirection(other, f), true);
  std::string out = EndSymbol(start, q, u, kArrowPx);
  if (it.text.empty()) return out;
  const Eigen::Vector2d at = q + 14 * n;
  const bool flip = n.x() < -0.3 || at.x() + TextWidth(it.text, it.size) > width_ - 2;
  return out + TextTag(at.x(), at.y() + 4, it.size, flip ? "end" : "start", it.text);
}

std::string SvgFigure::ItemTag(const Item& it, const Frame& f) const {
  std::ostringstream os;
  os.precision(6);
  const Eigen::Vector2d q = f.Map(it.points[0]);
  if (it.kind == Kind::kPolyline) {
    os << "<polyline " << (axes_ ? "clip-path=\"url(#plot)\" " : "") << StyleAttr(it.style)
       << " stroke-linejoin=\"round\" points=\"";
    for (const auto& p : it.points)
      if (p.allFinite()) os << f.Map(p).x() << "," << f.Map(p).y() << " ";
    os << "\"/>\n";
  } else if (it.kind == Kind::kMarker) {
    os << "<circle cx=\"" << q.x() << "\" cy=\"" << q.y() << "\" r=\"" << it.size << "\" " << StyleAttr(it.style)
       << "/>\n";
  } else if (it.kind == Kind::kText) {
    const bool flip = q.x() + 4 + TextWidth(it.text, it.size) > width_ - 2;
    const double dx = axes_ ? 4 : 0, dy = axes_ ? 4 : 0;  // without axes: at the point, as the caller placed it
    os << TextTag(flip ? q.x() - dx : q.x() + dx,
                  q.y() - dy,
                  it.size,
                  flip ? "end" : "start",
                  it.text,
                  " fill=\"" + it.style.stroke + "\"");
  } else {
    os << EndItem(it, f);
  }
  return os.str();
}

std::string SvgFigure::Render() const {
  std::vector<LegendItem> legend;
  for (const LegendEntry& e : legend_) legend.push_back({e.text, e.style, e.swatch, false});
  const Frame f = Layout(legend);
  std::ostringstream os;
  os.precision(6);
  os << SvgOpen(width_, f.height) << TitleLines(f.title, width_);
  if (!axes_) {
    for (const Item& it : items_) os << ItemTag(it, f);
    return os.str() + "</svg>\n";
  }
  const double tick_count = std::max(3.0, std::min(f.w, f.h) / 70.0);
  const Eigen::Vector2d span = f.hi - f.lo;
  const double step_x =
      NiceStep(equal_aspect_ ? span.maxCoeff() * std::min(f.w, f.h) / std::max(f.w, f.h) : span.x(), tick_count);
  const double step_y = equal_aspect_ ? step_x : NiceStep(span.y(), tick_count);
  os << LinearTicks(true, f.lo.x(), f.hi.x(), step_x, f.left, f.top, f.w, f.h, [&](double v) {
    return f.Map({v, f.lo.y()}).x();
  });
  os << LinearTicks(false, f.lo.y(), f.hi.y(), step_y, f.left, f.top, f.w, f.h, [&](double v) {
    return f.Map({f.lo.x(), v}).y();
  });
  os << "<rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.w << "\" height=\"" << f.h
     << "\" fill=\"none\" stroke=\"black\"/>\n";
  os << AxisLabelTags(x_label_, y_label_, f.left, f.top, f.w, f.h);
  os << "<clipPath id=\"plot\"><rect x=\"" << f.left << "\" y=\"" << f.top << "\" width=\"" << f.w << "\" height=\""
     << f.h << "\"/></clipPath>\n";
  for (const Item& it : items_) os << ItemTag(it, f);
  double legend_h = 0;
  os << LegendRows(legend, f.left, width_ - f.right, f.top + f.h + 50, &legend_h) << "</svg>\n";
  return os.str();
}

void SvgFigure::Write(const std::string& path) const { WriteOutput(path, Render()); }

Eigen::Vector2d CurveDirection(const std::vector<Eigen::Vector2d>& points, bool at_end) {
  if (points.size() < 2) return Eigen::Vector2d::Zero();
  Eigen::Vector2d lo = points.front(), hi = points.front();
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double eps = 1e-9 * std::max(1e-300, (hi - lo).maxCoeff());
  const std::size_t n = points.size();
  const Eigen::Vector2d& base = at_end ? points[n - 1] : points[0];
  for (std::size_t i = 1; i < n; ++i) {
    const Eigen::Vector2d& p = at_end ? points[n - 1 - i] : points[i];
    if ((p - base).norm() > eps) return at_end ? Eigen::Vector2d(base - p) : Eigen::Vector2d(p - base);
  }
  return Eigen::Vector2d::Zero();
}

namespace {

struct LogRange {
  double lo, hi;  // log10
};

// The data's log10 range of x (or y) over every series, widened to whole decades for y.
LogRange DataRange(const std::vector<LogLogSeries>& series, bool y_axis) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        const double v = std::log10(y_axis ? s.y[i] : s.x[i]);
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
  if (!std::isfinite(lo)) return {0, 1};
  if (y_axis) return {std::floor(lo), std::max(std::ceil(hi), std::floor(lo) + 1)};
  const double pad = std::max(0.05, 0.04 * (hi - lo));
  return {lo - pad, hi + pad};
}

// Decade ticks 10^k labelled, with 2..9 x 10^k minor ticks; when fewer than two decades fall in
// the range, the 2x and 5x ticks are labelled too.
std::string LogTicks(
    bool x_axis, LogRange r, const std::function<double(double)>& map, double left, double top, double w, double h) {
  std::ostringstream os;
  os.precision(6);
  int decades = 0;
  for (int d = static_cast<int>(std::ceil(r.lo - 1e-9)); d <= r.hi + 1e-9; ++d) ++decades;
  for (int d = static_cast<int>(std::floor(r.lo)); d <= static_cast<int>(std::ceil(r.hi)); ++d)
    for (int m = 1; m <= 9; ++m) {
      const double lv = d + std::log10(static_cast<double>(m));
      if (lv < r.lo - 1e-9 || lv > r.hi + 1e-9) continue;
      const double p = map(lv);
      const bool major = m == 1, labelled = major || (decades < 2 && (m == 2 || m == 5));
      const std::string grid = major ? "#cfcfcf" : "#eeeeee";
      const double tick = major ? 6 : 3;
      if (x_axis)
        os << "<line x1=\"" << p << "\" y1=\"" << top << "\" x2=\"" << p << "\" y2=\"" << top + h << "\" stroke=\""
           << grid << "\"/>\n<line x1=\"" << p << "\" y1=\"" << top + h << "\" x2=\"" << p << "\" y2=\""
           << top + h + tick << "\" stroke=\"black\"/>\n";
      else
        os << "<line x1=\"" << left << "\" y1=\"" << p << "\" x2=\"" << left + w << "\" y2=\"" << p << "\" stroke=\""
           << grid << "\"/>\n<line x1=\"" << left - tick << "\" y1=\"" << p << "\" x2=\"" << left << "\" y2=\"" << p
           << "\" stroke=\"black\"/>\n";
      if (!labelled) continue;
      std::ostringstream label;
      if (major && (d < -2 || d > 3))
        label << "1e" << d;
      else
        label << m * std::pow(10.0, d);
      os << (x_axis ? TextTag(p, top + h + 18, kFont, "middle", label.str())
                    : TextTag(left - 8, p + 4, kFont, "end", label.str()));
    }
  return os.str();
}

}  // namespace

std::string RenderLogLogChart(const std::string& title,
                              const std::string& x_label,
                              const std::string& y_label,
                              const std::vector<LogLogSeries>& series,
                              double width_px,
                              double height_px) {
  if (width_px <= 0) width_px = g_figure_size.width > 0 ? g_figure_size.width : 720;
  if (height_px <= 0) height_px = g_figure_size.height > 0 ? g_figure_size.height : 520;
  const LogRange rx = DataRange(series, false), ry = DataRange(series, true);
  const double left = 80, right = 24;
  const std::vector<std::string> title_lines = WrapTitle(title, width_px - 20, 15);
  const double top = 16 + 20.0 * static_cast<double>(title_lines.size());
  std::vector<LegendItem> legend_items;
  for (const auto& s : series) legend_items.push_back({s.label, s.style, SvgFigure::Swatch::kLine, s.markers});
  double legend_h = 0;
  LegendRows(legend_items, left, width_px - right, 0, &legend_h);
  const double w = width_px - left - right, h = std::max(80.0, height_px - top - 50 - legend_h - 8);
  auto X = [&](double lx) { return left + (lx - rx.lo) / (rx.hi - rx.lo) * w; };
  auto Y = [&](double ly) { return top + h - (ly - ry.lo) / (ry.hi - ry.lo) * h; };
  std::ostringstream os;
  os.precision(6);
  os << SvgOpen(width_px, height_px) << TitleLines(title_lines, width_px);
  os << LogTicks(true, rx, X, left, top, w, h) << LogTicks(false, ry, Y, left, top, w, h);
  os << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w << "\" height=\"" << h
     << "\" fill=\"none\" stroke=\"black\"/>\n";
  os << AxisLabelTags(x_label, y_label, left, top, w, h);
  for (const auto& s : series) {
    os << "<polyline " << StyleAttr(s.style) << " points=\"";
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) os << X(std::log10(s.x[i])) << "," << Y(std::log10(s.y[i])) << " ";
    os << "\"/>\n";
    if (s.markers)
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
        if (s.x[i] > 0 && s.y[i] > 0)
          os << "<circle cx=\"" << X(std::log10(s.x[i])) << "\" cy=\"" << Y(std::log10(s.y[i]))
             << "\" r=\"3.2\" fill=\"" << s.style.stroke << "\" stroke=\"" << s.style.stroke << "\"/>\n";
  }
  os << LegendRows(legend_items, left, width_px - right, top + h + 50, &legend_h) << "</svg>\n";
  return os.str();
}

}  // namespace plateball::tools
