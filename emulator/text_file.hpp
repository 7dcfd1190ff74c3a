#pragma once
// Reading a scenario (or any emulator input) file: a regular file no larger
// than the cap. A FIFO, a device or a directory is refused at once (opened
// non-blocking: a FIFO cannot hang the read, /dev/zero cannot feed
// gigabytes). Symlinks are followed: scenarios are test inputs a user
// points at. The emulator's twin of drivers/storage/regular_file.hpp
// (emulator/ does not include drivers/).
#include <cstddef>
#include <string>
#include <string_view>

namespace tnv::emu {

// The whole file; false with `error` set ("<path>: <why>").
bool read_text_file(const std::string& path, std::size_t max_bytes, std::string& text, std::string& error);

// `text` with its line breaks as spaces: a key or value quoted from a file
// into a one-line error message.
std::string one_line(std::string_view text);

}  // namespace tnv::emu
