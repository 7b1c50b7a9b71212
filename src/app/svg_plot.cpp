#include "app/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace ps {

namespace {

constexpr double kPanelW = 420, kPanelH = 320, kLeft = 62, kRight = 130, kTop = 30, kBottom = 48;
const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000", "#aec7e8"};

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

// "1e-3" style tick labels at powers of ten.
std::string decade(int e) { return e == 0 ? "1" : e == 1 ? "10" : "1e" + std::to_string(e); }

void panel(std::ostringstream& o, const PlotPanel& p, double ox, double oy, std::map<std::string, int>& colourOf) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const PlotSeries& s : p.series)
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
            if (s.x[i] > 0 && s.y[i] > 0) {
                x0 = std::min(x0, std::log10(s.x[i])), x1 = std::max(x1, std::log10(s.x[i]));
                y0 = std::min(y0, std::log10(s.y[i])), y1 = std::max(y1, std::log10(s.y[i]));
            }
    if (!(x0 <= x1)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    x0 = std::floor(x0), x1 = std::max(std::ceil(x1), x0 + 1);
    y0 = std::floor(y0), y1 = std::max(std::ceil(y1), y0 + 1);
    const double w = kPanelW - kLeft - kRight, h = kPanelH - kTop - kBottom;
    auto px = [&](double lx) { return ox + kLeft + (lx - x0) / (x1 - x0) * w; };
    auto py = [&](double ly) { return oy + kTop + (y1 - ly) / (y1 - y0) * h; };

    o << "<text x=\"" << num(ox + kLeft + w / 2) << "\" y=\"" << num(oy + 18)
      << "\" text-anchor=\"middle\" font-weight=\"bold\">" << escape(p.title) << "</text>\n";
    o << "<rect x=\"" << num(px(x0)) << "\" y=\"" << num(py(y1)) << "\" width=\"" << num(w) << "\" height=\"" << num(h)
      << "\" fill=\"none\" stroke=\"#000\"/>\n";
    for (int e = int(x0); e <= int(x1); ++e) {
        o << "<line x1=\"" << num(px(e)) << "\" y1=\"" << num(py(y0)) << "\" x2=\"" << num(px(e)) << "\" y2=\""
          << num(py(y1)) << "\" stroke=\"#ddd\"/>\n";
        o << "<text x=\"" << num(px(e)) << "\" y=\"" << num(py(y0) + 14) << "\" text-anchor=\"middle\">" << decade(e)
          << "</text>\n";
    }
    for (int e = int(y0); e <= int(y1); ++e) {
        o << "<line x1=\"" << num(px(x0)) << "\" y1=\"" << num(py(e)) << "\" x2=\"" << num(px(x1)) << "\" y2=\""
          << num(py(e)) << "\" stroke=\"#ddd\"/>\n";
        o << "<text x=\"" << num(px(x0) - 4) << "\" y=\"" << num(py(e) + 4) << "\" text-anchor=\"end\">" << decade(e)
          << "</text>\n";
    }
    o << "<text x=\"" << num(ox + kLeft + w / 2) << "\" y=\"" << num(oy + kPanelH - 12)
      << "\" text-anchor=\"middle\">" << escape(p.xLabel) << "</text>\n";
    double ly = oy + kTop + h / 2;
    o << "<text x=\"" << num(ox + 14) << "\" y=\"" << num(ly) << "\" text-anchor=\"middle\" transform=\"rotate(-90 "
      << num(ox + 14) << ' ' << num(ly) << ")\">" << escape(p.yLabel) << "</text>\n";

    int row = 0;
    for (const PlotSeries& s : p.series) {
        auto [it, fresh] = colourOf.try_emplace(s.label, int(colourOf.size()));
        const char* colour = kColours[size_t(it->second) % std::size(kColours)];
        o << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
            if (s.x[i] > 0 && s.y[i] > 0) o << num(px(std::log10(s.x[i]))) << ',' << num(py(std::log10(s.y[i]))) << ' ';
        o << "\"/>\n";
        double lx = ox + kPanelW - kRight + 10, lyy = oy + kTop + 8 + 15 * row++;
        o << "<line x1=\"" << num(lx) << "\" y1=\"" << num(lyy) << "\" x2=\"" << num(lx + 18) << "\" y2=\"" << num(lyy)
          << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n";
        o << "<text x=\"" << num(lx + 22) << "\" y=\"" << num(lyy + 4) << "\">" << escape(s.label) << "</text>\n";
    }
}

}  // namespace

std::string logLogPlotSvg(const std::vector<PlotPanel>& panels, int columns) {
    columns = std::max(1, std::min(columns, int(panels.size())));
    int rows = (int(panels.size()) + columns - 1) / columns;
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(columns * kPanelW) << "\" height=\""
      << num(std::max(1, rows) * kPanelH) << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    std::map<std::string, int> colourOf;
    for (size_t i = 0; i < panels.size(); ++i)
        panel(o, panels[i], double(i % size_t(columns)) * kPanelW, double(i / size_t(columns)) * kPanelH, colourOf);
    o << "</svg>\n";
    return o.str();
}

}  // namespace ps
