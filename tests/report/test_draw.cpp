// Rasteriser and font: coverage counts are exact (shared edges counted once), lines are
// at least 2 px wide, text lands where asked.
#include <catch2/catch.hpp>

#include "lib/report/bitmap_font.hpp"
#include "lib/report/draw.hpp"

using namespace gw;

TEST_CASE("a triangle covers exactly the pixel centres inside it", "[report][draw]") {
  CoverageRaster cov(10, 10);
  cov.add_triangle({0, 0}, {8, 0}, {0, 8});  // x + y < 8 (centres at +0.5)
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      const double s = x + 0.5 + y + 0.5;
      CAPTURE(x, y);
      if (s < 7.99) CHECK(cov.at(x, y) == 1);
      if (s > 8.01) CHECK(cov.at(x, y) == 0);
    }
  // Winding does not matter.
  CoverageRaster rev(10, 10);
  rev.add_triangle({0, 0}, {0, 8}, {8, 0});
  CHECK(rev.count == cov.count);
}

TEST_CASE("two triangles sharing an edge count each pixel once, centres on the edge included", "[report][draw]") {
  // A 6x6 square split along its diagonal: the diagonal passes exactly through pixel centres.
  CoverageRaster cov(8, 8);
  cov.add_triangle({1, 1}, {7, 1}, {7, 7});
  cov.add_triangle({1, 1}, {7, 7}, {1, 7});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      CAPTURE(x, y);
      const bool inside = x >= 1 && x < 7 && y >= 1 && y < 7;
      CHECK(cov.at(x, y) == (inside ? 1 : 0));
    }
  // A closed surface seen from outside: every interior pixel is covered twice (front and back wall).
  CoverageRaster two(8, 8);
  for (int k = 0; k < 2; ++k) {
    two.add_triangle({1, 1}, {7, 1}, {7, 7});
    two.add_triangle({1, 1}, {7, 7}, {1, 7});
  }
  CHECK(two.at(3, 3) == 2);
  CHECK(two.at(0, 0) == 0);
}

TEST_CASE("degenerate, non-finite and off-image triangles are harmless", "[report][draw]") {
  CoverageRaster cov(5, 5);
  cov.add_triangle({0, 0}, {4, 4}, {2, 2});  // zero area
  cov.add_triangle({0, 0}, {NAN, 1}, {2, 2});
  cov.add_triangle({-1e12, 0}, {1e12, 0}, {0, 1e12});
  cov.add_triangle({100, 100}, {110, 100}, {100, 110});
  for (auto c : cov.count) CHECK(c == 0);
  CoverageRaster big(5, 5);
  big.add_triangle({-50, -50}, {100, -50}, {-50, 100});  // covers the whole image
  for (auto c : big.count) CHECK(c == 1);
}

TEST_CASE("segments are at least 2 px wide and clip at the border", "[report][draw]") {
  Image img(20, 20, {255, 255, 255});
  const Rgb red{255, 0, 0};
  draw_segment(img, {2, 10}, {18, 10}, 2.0, red);
  int column = 0;
  for (int y = 0; y < 20; ++y) column += img.at(10, y) == red ? 1 : 0;
  CHECK(column == 2);
  CHECK(img.at(10, 9) == red);
  CHECK(img.at(10, 10) == red);
  CHECK(img.at(10, 5) == Rgb{255, 255, 255});
  draw_segment(img, {-100, -100}, {100, 100}, 3.0, red);  // crosses the image: no crash
  CHECK(img.at(15, 15) == red);
  draw_segment(img, {NAN, 0}, {5, 5}, 3.0, red);
}

TEST_CASE("text is drawn glyph by glyph at the requested scale", "[report][draw]") {
  CHECK(text_width("", 2) == 0);
  CHECK(text_width("AB", 1) == 11);
  CHECK(text_width("AB", 3) == 33);
  CHECK(glyph_pixel('|', 2, 0));
  CHECK_FALSE(glyph_pixel(' ', 2, 3));
  CHECK(glyph_pixel('\x01', 1, 1) == glyph_pixel('?', 1, 1));  // unknown -> '?'
  // Every printable character but space has ink, and no two glyphs are identical.
  for (int c = 33; c <= 126; ++c) {
    bool ink = false;
    for (int r = 0; r < kGlyphHeight; ++r)
      for (int col = 0; col < kGlyphWidth; ++col) ink = ink || glyph_pixel(static_cast<char>(c), col, r);
    CAPTURE(static_cast<char>(c));
    CHECK(ink);
    for (int d = 33; d < c; ++d) {
      bool same = true;
      for (int r = 0; r < kGlyphHeight; ++r)
        for (int col = 0; col < kGlyphWidth; ++col)
          same = same && glyph_pixel(static_cast<char>(c), col, r) == glyph_pixel(static_cast<char>(d), col, r);
      CAPTURE(static_cast<char>(d));
      CHECK_FALSE(same);
    }
  }
  Image img(40, 20, {255, 255, 255});
  const Rgb black{0, 0, 0};
  draw_text(img, 3, 2, "I", black, 2);  // 'I' top row ".###." -> columns 1..3, scaled x2
  CHECK(img.at(3 + 2, 2) == black);
  CHECK(img.at(3 + 7, 3) == black);
  CHECK(img.at(3, 2) == Rgb{255, 255, 255});
  CHECK(img.at(30, 10) == Rgb{255, 255, 255});
}
