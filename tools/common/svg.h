// SVG drawing for the command-line tools: a plate figure in world coordinates (paths on the
// plate, as in the paper's Figure 7) and a log-log chart (convergence studies). Both draw axes
// with ticks and labels, keep every mark inside the canvas, and put the legend under the plot so
// that it never covers a curve; legend swatches are drawn as the marks they name (a line with its
// dash pattern, a point as a point, the start and goal symbols as themselves).
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plateball::tools {

struct LegendItem;

/// The size of the figures a run draws, in pixels: --figure-size WxH (AddFigureSizeOption), else
/// 640 wide with the height fitted to the drawing (height 0) for plate figures and 720x520 for
/// charts.
struct FigureSize {
  double width = 0;   ///< 0: the figure's default
  double height = 0;  ///< 0: the figure's default (plate figures: fitted to the drawing)
};
/// Parses "WxH" (each an integer in [200, 8000]); throws std::invalid_argument
/// "command line: OPTION: value "TEXT": ...".
FigureSize ParseFigureSize(const std::string& option, const std::string& text);
/// Adds --figure-size WxH to `app`; the size is used by every figure drawn afterwards in the run.
void AddFigureSizeOption(CLI::App& app);
/// The size set by --figure-size (zeros when not given).
FigureSize CurrentFigureSize();
void SetFigureSize(const FigureSize& size);

/// A plate figure whose world box is fitted to everything drawn; y points up as on the plate, the
/// aspect is 1:1 (EqualAspect(false) for other charts), the axes are labelled in ball radii.
class SvgFigure {
 public:
  struct Style {
    std::string stroke = "black";
    double width = 1.5;  ///< in pixels
    std::string dash;    ///< e.g. "6,4"; empty = solid
    std::string fill = "none";
  };
  /// How a legend entry's swatch is drawn: kAuto is a point for a filled style, else a line.
  enum class Swatch { kAuto, kLine, kPoint, kStart, kGoal };

  /// The size of --figure-size, else 640 wide and fitted in height.
  SvgFigure();
  SvgFigure(double width_px, double height_px) : width_(width_px), height_(height_px) {}

  void Polyline(const std::vector<Eigen::Vector2d>& points, const Style& style);
  /// A marker of radius `radius_px` pixels at a world point.
  void Marker(const Eigen::Vector2d& p, double radius_px, const Style& style);
  /// Text at a world point (font size in pixels); moved left of the point when it would leave the
  /// canvas.
  void Text(const Eigen::Vector2d& p, const std::string& text, double size_px = 13, const std::string& color = "black");
  /// The start point (filled green disc) with an arrow along `direction` (the direction of motion;
  /// zero: no arrow), labelled `label` next to it; adds the legend entry "start (arrow: direction
  /// of motion)" once.
  void Start(const Eigen::Vector2d& p, const Eigen::Vector2d& direction, const std::string& label);
  /// The goal (black ring) with an arrow along the direction of arrival; legend entry "goal".
  void Goal(const Eigen::Vector2d& p, const Eigen::Vector2d& direction, const std::string& label);
  /// A legend entry under the plot.
  void Legend(const std::string& text, const Style& style, Swatch swatch = Swatch::kAuto);
  void Title(const std::string& title) { title_ = title; }
  void AxisLabels(const std::string& x_label, const std::string& y_label) { x_label_ = x_label, y_label_ = y_label; }
  /// Keep the aspect ratio 1:1 (plate figures); false for charts.
  void EqualAspect(bool equal) { equal_aspect_ = equal; }
  /// false: no axes, ticks or clipping; the world box (padded by 6%) fills the canvas less a 40 px
  /// margin (50 px on top with a title), for a caller that draws its own chart in pixel units.
  void Axes(bool axes) { axes_ = axes; }

  std::string Render() const;
  /// Writes Render() to `path` ("-": standard output) atomically (output_file.h); throws IoError
  /// (errors.h) when it cannot.
  void Write(const std::string& path) const;

 private:
  enum class Kind { kPolyline, kMarker, kText, kStart, kGoal };
  struct Item {
    Kind kind;
    std::vector<Eigen::Vector2d> points;  ///< kStart/kGoal: the point and the direction
    Style style;
    double size = 0;
    std::string text;
  };
  struct LegendEntry {
    std::string text;
    Style style;
    Swatch swatch;
  };
  struct Frame;
  Frame Layout(const std::vector<LegendItem>& legend) const;
  Eigen::Vector2d ArrowDirection(const Item& it, const Frame& f) const;
  std::string EndItem(const Item& it, const Frame& f) const;
  std::string ItemTag(const Item& it, const Frame& f) const;
  void AddEnd(Kind kind, const Eigen::Vector2d& p, const Eigen::Vector2d& direction, const std::string& label);
  double width_, height_;
  bool equal_aspect_ = true;
  bool axes_ = true;
  std::string title_;
  std::string x_label_ = "x (ball radii)", y_label_ = "y (ball radii)";
  std::vector<Item> items_;
  std::vector<LegendEntry> legend_;
};

/// The direction of a sampled curve at its start (at_end false) or its end: the chord to the
/// first point farther than 1e-9 of the curve's extent; zero for a curve of one point.
Eigen::Vector2d CurveDirection(const std::vector<Eigen::Vector2d>& points, bool at_end);

/// A log-log chart of series (x > 0, y > 0) with decade ticks and grid lines on both axes.
struct LogLogSeries {
  std::string label;
  std::vector<double> x, y;
  SvgFigure::Style style;
  bool markers = true;
};
/// width_px/height_px 0: --figure-size, else 720 x 520.
std::string RenderLogLogChart(const std::string& title,
                              const std::string& x_label,
                              const std::string& y_label,
                              const std::vector<LogLogSeries>& series,
                              double width_px = 0,
                              double height_px = 0);

}  // namespace plateball::tools
