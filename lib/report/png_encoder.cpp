#include "lib/report/png_encoder.hpp"

#include <png.h>

#include <csetjmp>
#include <stdexcept>

#include "lib/report/atomic_write.hpp"

namespace gw {
namespace {

struct WriteState {
  std::vector<std::uint8_t>* out;
  std::string error;
};

void append_bytes(png_structp png, png_bytep data, png_size_t n) {
  auto* state = static_cast<WriteState*>(png_get_io_ptr(png));
  state->out->insert(state->out->end(), data, data + n);
}

void flush_nothing(png_structp) {}

// libpng reports errors through longjmp: keep the message, then jump back to encode_png.
[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<WriteState*>(png_get_error_ptr(png));
  state->error = message ? message : "unknown error";
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& img) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgb.size() != static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3)
    throw std::invalid_argument("encode_png: image " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                                " has " + std::to_string(img.rgb.size()) + " bytes of pixels");
  std::vector<std::uint8_t> out;
  WriteState state{&out, {}};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
  if (!png) throw std::runtime_error("encode_png: libpng cannot start (out of memory)");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("encode_png: libpng cannot start (out of memory)");
  }
  std::vector<png_const_bytep> rows(static_cast<std::size_t>(img.height));
  for (int y = 0; y < img.height; ++y) rows[static_cast<std::size_t>(y)] = img.rgb.data() + img.index(0, y);
  // Nothing with a destructor may be created between setjmp and the end of libpng's calls.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("encode_png: libpng: " + state.error);
  }
  png_set_write_fn(png, &state, append_bytes, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, const_cast<png_bytepp>(rows.data()));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

void write_png(const Image& img, const std::string& path) {
  const std::vector<std::uint8_t> bytes = encode_png(img);
  write_file_atomic(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace gw
