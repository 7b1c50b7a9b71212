// A hand-written SVG log-log plot: panels of polylines with labelled axes and a legend.
// Just enough for `pathspace mc --svg` (RMSE against N per technique).
#pragma once
#include <string>
#include <vector>

namespace ps {

struct PlotSeries {
    std::string label;
    std::vector<double> x, y;  // points with x or y <= 0 are left out
};

struct PlotPanel {
    std::string title, xLabel, yLabel;
    std::vector<PlotSeries> series;
};

// Panels laid out in a grid `columns` wide; the colour of a label is the same in every panel.
std::string logLogPlotSvg(const std::vector<PlotPanel>& panels, int columns);

}  // namespace ps
