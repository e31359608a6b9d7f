// `pathlab points`: the points one pixel receives in two dimensions, as CSV, or
// drawn beside their radially averaged power spectrum (SVG or PNG).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <tuple>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image.h"
#include "core/seed.h"
#include "sampling/pixel_points.h"
#include "sampling/spectrum.h"

namespace pathlab::cli {
namespace {

// The renderer's limit on samples per pixel (validateRenderSettings).
constexpr int64_t kMaxSpp = int64_t(1) << 24;

struct PointsOptions {
    std::string sampler, dims, pixel = "0,0", resolution, output;
    std::string seed = "0";  // parseSeed
    int count = 0;
    int64_t spp = 0;        // read wide, so an absurd count is refused by range
    bool sppGiven = false;  // else the sampler is built for --count samples
};

// The options, checked and converted: what the sampler is built from.
struct PointsRequest {
    int dimX = 0, dimY = 1;
    Vec2i pixel, resolution;
    int spp = 0;
    uint64_t seed = 0;
};

std::pair<int, int> parsePair(const std::string& text, const std::string& option, char sep) {
    static const std::regex comma(R"((\d{1,7}),(\d{1,7}))"), times(R"((\d{1,6})x(\d{1,6}))");
    std::smatch m;
    if (!std::regex_match(text, m, sep == ',' ? comma : times))
        throw InputError(option + " must look like " + (sep == ',' ? "A,B" : "WxH") +
                         " with non-negative integers, got '" + text + "'");
    return {std::stoi(m[1]), std::stoi(m[2])};
}

std::string extensionOf(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

std::string svgDrawing(const std::vector<Vec2f>& pts, const std::vector<double>& spectrum,
                       const std::string& title) {
    const double panel = 400, margin = 30, gap = 60;
    const double left = margin, right = margin + panel + gap, top = margin + 20;
    std::ostringstream s;
    s.precision(5);
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << 2 * panel + gap + 2 * margin
      << "\" height=\"" << panel + 2 * margin + 40
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left << "\" y=\"" << margin << "\">" << title << "</text>\n"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << panel << "\" height=\""
      << panel << "\" fill=\"none\" stroke=\"#888\"/>\n";
    const double radius = std::clamp(panel / std::sqrt(double(pts.size()) + 1) / 6, 0.8, 4.0);
    for (const Vec2f& p : pts)
        s << "<circle cx=\"" << left + p.x * panel << "\" cy=\"" << top + (1 - p.y) * panel
          << "\" r=\"" << radius << "\"/>\n";
    // Spectrum: power against frequency, white-noise level 1 dashed.
    const int f = int(spectrum.size()) - 1;
    double ymax = 2;
    for (int r = 1; r <= f; ++r) ymax = std::max(ymax, spectrum[r]);
    ymax = std::min(ymax * 1.05, 8.0);
    const auto px = [&](double r) { return right + r / f * panel; };
    const auto py = [&](double v) { return top + panel - std::min(v, ymax) / ymax * panel; };
    s << "<rect x=\"" << right << "\" y=\"" << top << "\" width=\"" << panel << "\" height=\""
      << panel << "\" fill=\"none\" stroke=\"#888\"/>\n"
      << "<line x1=\"" << right << "\" y1=\"" << py(1) << "\" x2=\"" << right + panel << "\" y2=\""
      << py(1) << "\" stroke=\"#888\" stroke-dasharray=\"4 4\"/>\n<polyline fill=\"none\" "
      << "stroke=\"#1f5fbf\" stroke-width=\"1.5\" points=\"";
    for (int r = 1; r <= f; ++r) s << px(r) << ',' << py(spectrum[r]) << ' ';
    // The caption in two lines: one would run past the drawing's right edge.
    s << "\"/>\n<text x=\"" << right << "\" y=\"" << top + panel + 18
      << "\">radially averaged power spectrum, frequency 0.." << f << "</text>\n<text x=\"" << right
      << "\" y=\"" << top + panel + 34 << "\">power 0.." << ymax
      << " (dashed: white noise, 1)</text>\n<text x=\"" << left << "\" y=\"" << top + panel + 18
      << "\">points in [0,1)^2</text>\n</svg>\n";
    return s.str();
}

Image pngDrawing(const std::vector<Vec2f>& pts, const std::vector<double>& spectrum) {
    const int panel = 400, margin = 20, gap = 40;
    Image img(2 * panel + gap + 2 * margin, panel + 2 * margin);
    std::fill(img.rgb.begin(), img.rgb.end(), 1.0f);
    const auto plot = [&](int x, int y, Vec3f c) {
        if (x >= 0 && y >= 0 && x < img.width && y < img.height) img.set(x, y, c);
    };
    const auto frame = [&](int x0) {
        for (int i = 0; i <= panel; ++i) {
            const Vec3f grey(0.55f);
            plot(x0 + i, margin, grey), plot(x0 + i, margin + panel, grey);
            plot(x0, margin + i, grey), plot(x0 + panel, margin + i, grey);
        }
    };
    const int left = margin, right = margin + panel + gap;
    frame(left), frame(right);
    for (const Vec2f& p : pts) {
        const int cx = left + int(p.x * panel), cy = margin + int((1 - p.y) * panel);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) plot(cx + dx, cy + dy, Vec3f(0.0f));
    }
    const int f = int(spectrum.size()) - 1;
    double ymax = 2;
    for (int r = 1; r <= f; ++r) ymax = std::max(ymax, spectrum[r]);
    ymax = std::min(ymax * 1.05, 8.0);
    const auto sy = [&](double v) { return margin + panel - std::min(v, ymax) / ymax * panel; };
    for (int i = 0; i < panel; i += 8)
        for (int k = 0; k < 4; ++k) plot(right + i + k, int(std::lround(sy(1))), Vec3f(0.5f));
    // The spectrum as a polyline, drawn by sampling each segment densely.
    const Vec3f blue(0.02f, 0.12f, 0.55f);
    for (int r = 1; r < f; ++r) {
        const double x0 = right + double(r) / f * panel, x1 = right + double(r + 1) / f * panel;
        const double y0 = sy(spectrum[r]), y1 = sy(spectrum[r + 1]);
        const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) * 2 + 1;
        for (int t = 0; t <= steps; ++t) {
            const double a = double(t) / steps;
            const int x = int(std::lround(x0 + a * (x1 - x0))),
                      y = int(std::lround(y0 + a * (y1 - y0)));
            plot(x, y, blue), plot(x, y + 1, blue);
        }
    }
    return img;
}

std::string sizeRange() {
    return "between 1x1 and " + std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide);
}

// The image the sampler maps onto: --resolution, or the smallest holding
// the pixel; never larger than an image pathlab renders.
Vec2i pointsResolution(const PointsOptions& o, Vec2i pixel) {
    if (o.resolution.empty()) {
        if (pixel.x >= kMaxImageSide || pixel.y >= kMaxImageSide)
            throw InputError("--pixel must lie in an image " + sizeRange() + ", got '" + o.pixel +
                             "'");
        return {pixel.x + 1, pixel.y + 1};
    }
    const auto [w, h] = parsePair(o.resolution, "--resolution", 'x');
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw InputError("--resolution must be " + sizeRange() + ", got '" + o.resolution + "'");
    if (pixel.x >= w || pixel.y >= h)
        throw InputError("--pixel " + o.pixel + " is not inside --resolution " + o.resolution);
    return {w, h};
}

PointsRequest pointsRequest(const PointsOptions& o) {
    if (o.count < 1 || o.count > (1 << 22))
        throw InputError("--count must be between 1 and 4194304, got " + std::to_string(o.count));
    if (o.sppGiven && (o.spp < 1 || o.spp > kMaxSpp))
        throw InputError("--spp must be between 1 and " + std::to_string(kMaxSpp) + ", got " +
                         std::to_string(o.spp));
    PointsRequest r;
    std::tie(r.dimX, r.dimY) = parsePair(o.dims, "--dims", ',');
    // One dimension against itself is a diagonal line, never a layout.
    if (r.dimX == r.dimY)
        throw InputError("--dims must name two different dimensions, got '" + o.dims + "'");
    const auto [px, py] = parsePair(o.pixel, "--pixel", ',');
    r.pixel = {px, py};
    r.resolution = pointsResolution(o, r.pixel);
    r.spp = o.sppGiven ? int(o.spp) : o.count;
    r.seed = parseSeed(o.seed);
    return r;
}

void runPoints(const PointsOptions& o) {
    const std::string ext = extensionOf(o.output);
    if (ext != ".csv" && ext != ".svg" && ext != ".png")
        throw InputError("-o must end in .csv, .svg or .png, got '" + o.output + "'");
    const PointsRequest r = pointsRequest(o);
    const int i = r.dimX, j = r.dimY, px = r.pixel.x, py = r.pixel.y;
    const std::vector<Vec2f> pts =
        pixelPoints({o.sampler, o.count, i, j, r.pixel, r.resolution, r.spp, r.seed});

    if (ext == ".csv") {
        std::string text = "index,x,y\n";
        char line[96];
        for (int k = 0; k < o.count; ++k) {
            std::snprintf(line, sizeof line, "%d,%.9g,%.9g\n", k, pts[k].x, pts[k].y);
            text += line;
        }
        writeFileAtomic(o.output, text);
        return;
    }
    if (ext == ".png") checkWritable(o.output);
    const std::vector<double> spectrum = radialPowerSpectrum(pts, spectrumFrequency(pts.size()));
    if (ext == ".svg") {
        const std::string title = o.sampler + ", dims " + std::to_string(i) + "," +
                                  std::to_string(j) + ", pixel " + std::to_string(px) + "," +
                                  std::to_string(py) + ", " + std::to_string(o.count) +
                                  " points, seed " + std::to_string(r.seed);
        writeFileAtomic(o.output, svgDrawing(pts, spectrum, title));
    } else {
        writeImage(o.output, pngDrawing(pts, spectrum));
    }
}

}  // namespace

void addPointsCommand(CLI::App& app) {
    auto opts = std::make_shared<PointsOptions>();
    CLI::App* cmd = app.add_subcommand(
        "points",
        "Write the points a pixel receives in two dimensions (CSV, or SVG/PNG with spectrum)");
    cmd->add_option("--sampler", opts->sampler, "Sampler name (see `pathlab samplers`)")
        ->required();
    cmd->add_option("--count", opts->count, "Number of samples (indices 0..N-1)")->required();
    cmd->add_option("--dims", opts->dims,
                    "Two different dimensions I,J of the layout (0,1 = pixel)")
        ->required();
    cmd->add_option("--pixel", opts->pixel, "Pixel X,Y")->capture_default_str();
    cmd->add_option("--seed", opts->seed, "Seed")->capture_default_str();
    CLI::Option* spp = cmd->add_option(
        "--spp", opts->spp, "Samples per pixel of the sampler, 1 to 16777216 (default: --count)");
    cmd->add_option(
        "--resolution", opts->resolution,
        "Image size WxH the sampler maps onto (default: the smallest containing the pixel)");
    cmd->add_option("-o,--output", opts->output, "Output file: .csv (index,x,y), .svg or .png")
        ->required();
    cmd->callback([opts, spp] {
        opts->sppGiven = spp->count() > 0;
        runPoints(*opts);
    });
}

}  // namespace pathlab::cli
