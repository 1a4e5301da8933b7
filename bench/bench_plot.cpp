// Rendering figures through gnuplot: the script, data inline, goes down a pipe, so only the
// PNG is left beside the experiment's CSV.
#include "bench_plot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <sstream>

namespace sap_bench {
namespace {

/// Filled circle, square, triangle, diamond, inverted triangle.
constexpr int kPointShapes[] = {7, 5, 9, 13, 11};

std::string quoted(const std::string& inText) {
  std::string out = "\"";
  for (char c : inText) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string number(double inValue) {
  if (!std::isfinite(inValue)) return "NaN";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", inValue);
  return buffer;
}

bool gnuplotAvailable() {
  static const bool available = std::system("command -v gnuplot >/dev/null 2>&1") == 0;
  return available;
}

/// Datablock name of series s of panel p.
std::string blockName(std::size_t p, std::size_t s) {
  return "$P" + std::to_string(p) + "S" + std::to_string(s);
}

/// Inline data: columns x, y, and the cumulative lower bound for stacked panels.
void writeData(std::ostream& ioScript, const Panel& inPanel, std::size_t inPanelIndex) {
  std::vector<double> below;
  for (std::size_t s = 0; s < inPanel.series.size(); ++s) {
    const Series& series = inPanel.series[s];
    below.resize(series.x.size(), 0.0);
    ioScript << blockName(inPanelIndex, s) << " << EOD\n";
    for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
      const double y = series.y[i];
      const bool stacked = inPanel.style == PlotStyle::kStacked;
      const double low = stacked ? below[i] : 0.0;
      const double high = stacked ? below[i] + y : y;
      ioScript << number(series.x[i]) << ' ' << number(high) << ' ' << number(low) << '\n';
      if (stacked) below[i] = high;
    }
    ioScript << "EOD\n";
  }
}

void writePanel(std::ostream& ioScript, const Panel& inPanel, std::size_t inPanelIndex) {
  ioScript << "set title " << quoted(inPanel.title) << "\n"
           << "set xlabel " << quoted(inPanel.xlabel) << "\n"
           << "set ylabel " << quoted(inPanel.ylabel) << "\n"
           << (inPanel.logx ? "set logscale x 2\n" : "unset logscale x\n")
           << (inPanel.logy ? "set logscale y\n" : "unset logscale y\n") << "set yrange "
           << (inPanel.yrange.empty() ? "[*:*]" : inPanel.yrange) << "\n";
  if (inPanel.xtics.empty()) {
    ioScript << "set xtics autofreq\n";
  } else {
    ioScript << "set xtics (";
    for (std::size_t i = 0; i < inPanel.xtics.size(); ++i) {
      ioScript << (i ? ", " : "") << quoted(inPanel.xtics[i].second) << ' '
               << number(inPanel.xtics[i].first);
    }
    ioScript << ") rotate by -30\n";
  }
  ioScript << "unset label\n";
  for (const auto& label : inPanel.labels) {
    ioScript << "set label " << quoted(label.second) << " at first " << number(label.first)
             << ", graph 0.92 center\n";
  }
  ioScript << "plot ";
  for (std::size_t s = 0; s < inPanel.series.size(); ++s) {
    const std::string title = quoted(inPanel.series[s].title);
    ioScript << (s ? ", \\\n     " : "") << blockName(inPanelIndex, s);
    switch (inPanel.style) {
      case PlotStyle::kStacked:
        ioScript << " using 1:3:2 with filledcurves title " << title;
        break;
      case PlotStyle::kLines:
        ioScript << " using 1:2 with lines lw 2 title " << title;
        break;
      case PlotStyle::kPoints:
        // gnuplot cycles 8 colours: the point shape changes with every cycle, so that a
        // legend of more series still names each point unambiguously.
        ioScript << " using 1:2 with points pt " << kPointShapes[(s / 8) % std::size(kPointShapes)]
                 << " ps 1.5 title " << title;
        break;
      case PlotStyle::kLinesPoints:
        ioScript << " using 1:2 with linespoints lw 2 pt 7 title " << title;
        break;
    }
  }
  ioScript << "\n";
}

}  // namespace

std::string renderFigure(const std::string& inDir, const Figure& inFigure) {
  const std::string png = inDir + "/" + inFigure.name + ".png";
  if (!gnuplotAvailable()) {
    std::cerr << "sap_bench: gnuplot not found, no " << png << "\n";
    return "";
  }
  const std::size_t panels = inFigure.panels.size();
  const std::size_t columns = inFigure.columns > 0 ? inFigure.columns : panels;
  const std::size_t rows = (panels + columns - 1) / columns;
  std::ostringstream script;
  script << "set terminal pngcairo size " << 560 * columns << "," << 420 * rows
         << " noenhanced font \"sans,10\"\n"
         << "set output " << quoted(png) << "\n"
         << "set grid\nset key outside below horizontal\nset style fill transparent solid 0.6 "
            "noborder\n";
  for (std::size_t p = 0; p < panels; ++p) writeData(script, inFigure.panels[p], p);
  script << "set multiplot layout " << rows << "," << columns << "\n";
  for (std::size_t p = 0; p < panels; ++p) writePanel(script, inFigure.panels[p], p);
  script << "unset multiplot\n";
  FILE* gnuplot = popen("gnuplot", "w");
  const std::string text = script.str();
  const bool written = gnuplot && std::fwrite(text.data(), 1, text.size(), gnuplot) == text.size();
  const bool finished = gnuplot && pclose(gnuplot) == 0;
  if (!written || !finished) {
    std::cerr << "sap_bench: gnuplot failed on " << png << "\n";
    return "";
  }
  return png;
}

}  // namespace sap_bench
