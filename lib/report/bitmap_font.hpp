#pragma once
// A 5x7 bitmap font (plus one descender row for g j p q y) for printable ASCII (32..126),
// drawn at an integer scale: labels and titles of the biplane PNG without a font library.
#include <string>

#include "lib/report/image.hpp"

namespace gw {

inline constexpr int kGlyphWidth = 5;    // pixels at scale 1
inline constexpr int kGlyphHeight = 8;   // 7 + descender row
inline constexpr int kGlyphAdvance = 6;  // glyph + one column of spacing

// True when pixel (col, row) of character `c`'s glyph is ink (row 0 at the top).
// Characters outside 32..126 are drawn as '?'; col/row outside the glyph are false.
bool glyph_pixel(char c, int col, int row);

// Width in pixels of `text` drawn at `scale` (no trailing spacing column); 0 when empty.
int text_width(const std::string& text, int scale = 1);

// Draws `text` with its top-left corner at (x, y), each font pixel a scale x scale block;
// clipped at the image border. With `halo`, a one-font-pixel outline in that colour is
// drawn first so the text stays readable over lines and silhouettes.
void draw_text(Image& img, int x, int y, const std::string& text, Rgb color, int scale = 1,
               const Rgb* halo = nullptr);

}  // namespace gw
