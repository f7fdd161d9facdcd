// Minimal SVG drawing for the command-line tools: a plane figure in world coordinates (paths on
// the plate, as in the paper's Figure 7) and a log-log chart (convergence studies).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace plateball::tools {

/// A figure whose world box is fitted to everything drawn; y points up as on the plate.
class SvgFigure {
 public:
  struct Style {
    std::string stroke = "black";
    double width = 1.5;         ///< in pixels
    std::string dash;           ///< e.g. "6,4"; empty = solid
    std::string fill = "none";
  };
  SvgFigure(double width_px = 640, double height_px = 640) : width_(width_px), height_(height_px) {}

  void Polyline(const std::vector<Eigen::Vector2d>& points, const Style& style);
  /// A marker of radius `radius_px` pixels at a world point.
  void Marker(const Eigen::Vector2d& p, double radius_px, const Style& style);
  /// Text at a world point (font size in pixels).
  void Text(const Eigen::Vector2d& p, const std::string& text, double size_px = 13, const std::string& color = "black");
  /// A legend line in the top-left corner (drawn after the figure).
  void Legend(const std::string& text, const Style& style);
  void Title(const std::string& title) { title_ = title; }
  /// Keep the aspect ratio 1:1 (plate figures; the canvas then ends below the drawing, so a wide
  /// drawing leaves no empty lower half); false for charts.
  void EqualAspect(bool equal) { equal_aspect_ = equal; }

  std::string Render() const;
  /// Writes Render() to `path` ("-": standard output) atomically (output_file.h); throws IoError
  /// (errors.h) when it cannot.
  void Write(const std::string& path) const;

 private:
  struct Item {
    int kind;  // 0 polyline, 1 marker, 2 text
    std::vector<Eigen::Vector2d> points;
    Style style;
    double size = 0;
    std::string text;
  };
  double width_, height_;
  bool equal_aspect_ = true;
  std::string title_;
  std::vector<Item> items_;
  std::vector<std::pair<std::string, Style>> legend_;
};

/// A log-log chart of series (x > 0, y > 0) with decade grid lines and labelled axes.
struct LogLogSeries {
  std::string label;
  std::vector<double> x, y;
  SvgFigure::Style style;
  bool markers = true;
};
std::string RenderLogLogChart(const std::string& title, const std::string& x_label, const std::string& y_label,
                              const std::vector<LogLogSeries>& series, double width_px = 720, double height_px = 520);

}  // namespace plateball::tools
