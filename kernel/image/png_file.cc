// SPDX-License-Identifier: GPL-3.0-or-later
#include "png_file.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::unique_ptr<std::FILE, FileCloser> Open(const std::string& path, const char* mode,
                                            const char* doing) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (f == nullptr) {
    throw InputError(path + ": cannot " + doing + " the picture (" + std::strerror(errno) + ")");
  }
  return std::unique_ptr<std::FILE, FileCloser>(f);
}

}  // namespace

void WritePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  auto f = Open(path, "wb", "write");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw InputError(path + ": writing the PNG failed");
  }
  png_init_io(png, f.get());
  png_set_compression_level(png, 1);  // runs take many pictures: speed over size
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    png_write_row(png, rgb.data() + static_cast<size_t>(y) * static_cast<size_t>(width) * 3);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

std::vector<uint8_t> ReadPng(const std::string& path, int* width, int* height) {
  auto f = Open(path, "rb", "read");
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<uint8_t> rgb;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError(path + ": not a readable PNG");
  }
  png_init_io(png, f.get());
  png_read_info(png, info);
  // whatever it holds, read 8-bit RGB
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  *width = static_cast<int>(png_get_image_width(png, info));
  *height = static_cast<int>(png_get_image_height(png, info));
  const size_t row = static_cast<size_t>(*width) * 3;
  rgb.resize(row * static_cast<size_t>(*height));
  for (int y = 0; y < *height; ++y)
    png_read_row(png, rgb.data() + row * static_cast<size_t>(y), nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return rgb;
}

}  // namespace unimouse
