// PNG plots through gnuplot: each figure becomes NAME.png next to the experiment's CSV when
// gnuplot is on PATH.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sap_bench {

/// One curve of a panel.
struct Series {
  std::string title;
  std::vector<double> x;
  std::vector<double> y;
  /// Appends the point (inX, inY).
  void add(double inX, double inY) {
    x.push_back(inX);
    y.push_back(inY);
  }
};

/// How a panel draws its series.
enum class PlotStyle { kLinesPoints, kLines, kPoints, kStacked };

/// One chart; kStacked fills each series on top of the previous ones (same x for all).
struct Panel {
  Panel() = default;
  Panel(std::string inTitle, std::string inXlabel, std::string inYlabel, bool inLogx = false,
        bool inLogy = false, PlotStyle inStyle = PlotStyle::kLinesPoints)
      : title(std::move(inTitle)),
        xlabel(std::move(inXlabel)),
        ylabel(std::move(inYlabel)),
        logx(inLogx),
        logy(inLogy),
        style(inStyle) {}

  std::string title;
  std::string xlabel;
  std::string ylabel;
  bool logx = false;
  bool logy = false;
  PlotStyle style = PlotStyle::kLinesPoints;
  std::vector<Series> series;
  std::vector<std::pair<double, std::string>> xtics;   ///< named ticks (empty: automatic)
  std::vector<std::pair<double, std::string>> labels;  ///< text placed above x at the top
  std::string xrange;  ///< gnuplot range such as "[0:*]" (empty: automatic)
  std::string yrange;  ///< likewise for y
};

/// Panels side by side (columns) in one PNG.
struct Figure {
  Figure(std::string inName, std::vector<Panel> inPanels, int inColumns = 0)
      : name(std::move(inName)), panels(std::move(inPanels)), columns(inColumns) {}

  std::string name;  ///< file stem
  std::vector<Panel> panels;
  int columns = 0;  ///< 0: all panels in one row
};

/// Renders DIR/NAME.png with gnuplot. Returns its path, or an empty string (and a line on
/// stderr) when gnuplot is missing or fails.
std::string renderFigure(const std::string& inDir, const Figure& inFigure);

}  // namespace sap_bench
