// The PNG figure writer (analysis/figures/figure_png): read back with cairo's PNG decoder and
// checked pixel by pixel against the layout's closed form.
#include "analysis/figures/figure_png.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::figures {
namespace {

namespace fs = std::filesystem;

struct Image {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface{nullptr,
                                                                             cairo_surface_destroy};
  int width() const { return cairo_image_surface_get_width(surface.get()); }
  int height() const { return cairo_image_surface_get_height(surface.get()); }
  Rgb at(int x, int y) const {
    const unsigned char* row =
        cairo_image_surface_get_data(surface.get()) +
        static_cast<std::ptrdiff_t>(y) * cairo_image_surface_get_stride(surface.get());
    std::uint32_t pixel = 0;
    std::memcpy(&pixel, row + 4 * x, 4);  // native-endian 0xAARRGGBB
    return {static_cast<int>((pixel >> 16) & 0xff), static_cast<int>((pixel >> 8) & 0xff),
            static_cast<int>(pixel & 0xff)};
  }
  // Within 40 per channel of `c`: antialiasing blends the edges of lines with the background.
  bool near(int x, int y, const Rgb& c) const {
    const Rgb p = at(x, y);
    return std::abs(p.red - c.red) < 40 && std::abs(p.green - c.green) < 40 &&
           std::abs(p.blue - c.blue) < 40;
  }
  int count(int x0, int y0, int x1, int y1, const Rgb& c) const {
    int n = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) n += near(x, y, c) ? 1 : 0;
    }
    return n;
  }
};

Image read_png(const std::string& path) {
  Image image;
  image.surface.reset(cairo_image_surface_create_from_png(path.c_str()));
  EXPECT_EQ(cairo_surface_status(image.surface.get()), CAIRO_STATUS_SUCCESS) << path;
  return image;
}

class FigurePngTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("oscilab_figure_png_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

const Rgb kBlue = palette_color(1);
const Rgb kVermillion = palette_color(2);
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST_F(FigurePngTest, WritesTheRequestedSizeWithEachPanelsSeriesInItsPanel) {
  Figure figure;
  figure.title = "test θ ± σ";  // non-ASCII text is drawn, not refused
  figure.width_px = 600;
  figure.panel_height_px = 300;
  // A curve that turns back in x (a fold) with a NaN gap, palette colour 1, and dots in colour 2
  // in a second panel.
  FigurePanel a{"upper", "f0 [N]", "amplitude [mm]", {}, true};
  a.series.push_back(
      {"HBM", FigureSeries::Style::Line, 1, {0, 1, 2, 1.5, kNan, 3}, {0, 1, 2, 3, kNan, 4}, 3.0});
  FigurePanel b{"", "f0 [N]", "z [mm]", {}, true};
  b.series.push_back({"map", FigureSeries::Style::Dots, 2, {0, 1, 2, 3}, {1, 2, 1, 2}, 6.0});
  figure.panels = {a, b};
  write_figure_png(figure, path("figure.png"));
  const Image image = read_png(path("figure.png"));
  ASSERT_EQ(image.width(), 600);
  ASSERT_EQ(image.height(), 2 * 300 + 30);  // the panels and the title row
  EXPECT_EQ(figure_height_px(figure), 630);
  EXPECT_GT(image.count(0, 0, 600, 330, kBlue), 300);
  EXPECT_GT(image.count(0, 330, 600, 630, kVermillion), 4 * 20);  // four dots of ~28 px
  EXPECT_EQ(image.count(0, 330, 600, 630, kBlue), 0);
  EXPECT_EQ(image.count(0, 0, 600, 330, kVermillion), 0);
}

// A diagonal from (0, 0) to (1, 1) spans the axes box less the margins: 4 % of the span on each
// side in x, 6 % in y. The box is the panel less 82 px left, 18 px right, 8 px top and 50 px
// bottom, so the line's ends sit at closed-form pixels (±3 px: the 3 px pen's round-off).
TEST_F(FigurePngTest, MapsDataToPixelsWithTheStatedMarginsAndTheYAxisUp) {
  Figure figure;
  figure.width_px = 600;
  figure.panel_height_px = 400;
  FigurePanel panel{"", "x", "y", {}, false};
  panel.series.push_back({"", FigureSeries::Style::Line, 1, {0.0, 1.0}, {0.0, 1.0}, 2.0});
  figure.panels = {panel};
  write_figure_png(figure, path("diagonal.png"));
  const Image image = read_png(path("diagonal.png"));
  const double left = 82.0, width = 600.0 - 82.0 - 18.0, top = 8.0, height = 400.0 - 8.0 - 50.0;
  const double x_first = left + width * 0.04 / 1.08, x_last = left + width * 1.04 / 1.08;
  const double y_first = top + height * 1.06 / 1.12, y_last = top + height * 0.06 / 1.12;
  int x_min = 600, x_max = -1, y_at_x_min = -1, y_at_x_max = -1;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (!image.near(x, y, kBlue)) continue;
      if (x < x_min) x_min = x, y_at_x_min = y;
      if (x > x_max) x_max = x, y_at_x_max = y;
    }
  }
  EXPECT_NEAR(x_min, x_first, 3.0);
  EXPECT_NEAR(x_max, x_last, 3.0);
  EXPECT_NEAR(y_at_x_min, y_first, 3.0);  // data y = 0 at the bottom
  EXPECT_NEAR(y_at_x_max, y_last, 3.0);   // data y = 1 at the top
}

TEST_F(FigurePngTest, BreaksLinesAtNan) {
  Figure figure;
  figure.width_px = 600;
  figure.panel_height_px = 300;
  FigurePanel panel{"", "x", "y", {}, false};
  panel.series.push_back(
      {"", FigureSeries::Style::Line, 1, {0, 1, kNan, 2, 3}, {0, 0, kNan, 0, 0}, 3.0});
  figure.panels = {panel};
  write_figure_png(figure, path("gap.png"));
  const Image image = read_png(path("gap.png"));
  const double left = 82.0, width = 600.0 - 82.0 - 18.0;
  const auto column = [&](double x_data) {
    return static_cast<int>(left + width * (x_data + 0.12) / 3.24);  // margins of 0.12 = 4 % of 3
  };
  EXPECT_GT(image.count(column(0.5), 0, column(0.5) + 1, 300, kBlue), 0);
  EXPECT_EQ(image.count(column(1.5) - 5, 0, column(1.5) + 5, 300, kBlue), 0);  // the gap
  EXPECT_GT(image.count(column(2.5), 0, column(2.5) + 1, 300, kBlue), 0);
}

TEST_F(FigurePngTest, RefusesWhatItCannotDrawOrWriteNamingTheFile) {
  Figure empty;
  try {
    write_figure_png(empty, path("empty.png"));
    FAIL() << "a figure without panels was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("empty.png: the figure has no panels"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(path("empty.png")));

  Figure figure;
  figure.panels.push_back({"", "x", "y", {}, false});
  const std::string missing_dir = path("no-such-dir/figure.png");
  try {
    write_figure_png(figure, missing_dir);
    FAIL() << "a PNG was written into a missing folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir + ": cannot write PNG"), std::string::npos)
        << e.what();
  }

  figure.width_px = 1000000;  // 4 TB of pixels: refused before any allocation
  EXPECT_THROW(write_figure_png(figure, path("huge.png")), InputError);
  EXPECT_FALSE(fs::exists(path("huge.png")));
}

// A panel with no finite point still shows its axes (0..1), and a single value is padded by
// ±10 % of itself, not divided by a zero span.
TEST_F(FigurePngTest, DrawsEmptyAndSinglePointPanels) {
  Figure figure;
  figure.width_px = 400;
  figure.panel_height_px = 200;
  figure.panels.push_back({"", "x", "y", {}, true});
  FigurePanel single{"", "x", "y", {}, true};
  single.series.push_back({"one", FigureSeries::Style::Markers, 2, {5.0}, {-3.0}, 9.0});
  single.series.push_back({"none", FigureSeries::Style::Line, 1, {kNan}, {kNan}, 2.0});
  figure.panels.push_back(single);
  write_figure_png(figure, path("degenerate.png"));
  const Image image = read_png(path("degenerate.png"));
  // The marker sits at the centre of the second panel's axes box.
  const int cx = static_cast<int>(82.0 + 0.5 * (400.0 - 82.0 - 18.0));
  const int cy = static_cast<int>(200.0 + 8.0 + 0.5 * (200.0 - 8.0 - 50.0));
  EXPECT_GT(image.count(cx - 6, cy - 6, cx + 7, cy + 7, kVermillion), 10);
}

}  // namespace
}  // namespace oscilab::figures
