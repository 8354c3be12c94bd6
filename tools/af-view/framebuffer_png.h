#pragma once
// The current OpenGL framebuffer written as a PNG file (cairo), through a temporary file renamed
// into place, so a picture cut short never replaces a good one.

#include <string>

namespace af::view {

// Reads the back buffer's (0, 0, width, height). Throws std::runtime_error naming the path when
// the file cannot be written.
void writeFramebufferPng(int width, int height, const std::string& path);

}  // namespace af::view
