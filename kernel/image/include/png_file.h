// SPDX-License-Identifier: GPL-3.0-or-later
// RGB pictures as PNG files.
#ifndef UNIMOUSE_IMAGE_PNG_FILE_H_
#define UNIMOUSE_IMAGE_PNG_FILE_H_

#include <cstdint>
#include <string>
#include <vector>

namespace unimouse {

/// Writes 8-bit RGB rows, top first. Throws InputError when the file cannot be written.
void WritePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

/// Reads a PNG as 8-bit RGB rows, top first, whatever its colour type. Throws InputError.
std::vector<uint8_t> ReadPng(const std::string& path, int* width, int* height);

}  // namespace unimouse

#endif  // UNIMOUSE_IMAGE_PNG_FILE_H_
