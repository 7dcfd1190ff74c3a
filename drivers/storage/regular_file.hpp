#pragma once
// Opening a file the daemon reads (config, parameter image): it must be a
// regular file no larger than a stated cap. A FIFO, a device or a directory
// is refused at once (opened non-blocking, so a FIFO cannot hang the read;
// /dev/zero cannot feed gigabytes). Whether a symlink at the path is
// followed is the caller's choice, per file (docs/install-board.md).
#include <cstddef>
#include <string>

namespace tnv::drivers {

enum class LinkPolicy : bool { refuse, follow };

struct RegularFile {
  int fd = -1;             // open, blocking, close-on-exec; -1 on failure
  std::size_t size = 0;    // bytes at open time
  bool missing = false;    // the path does not exist (no error text then)
  std::string error;       // "<path>: <why>" when fd < 0 and not missing
};

// The caller closes `fd`.
RegularFile open_regular_file(const std::string& path, std::size_t max_bytes, LinkPolicy links) noexcept;

// The whole file as text; false with `error` set ("<path>: <why>").
bool read_regular_file(const std::string& path, std::size_t max_bytes, LinkPolicy links, std::string& text,
                       std::string& error);

}  // namespace tnv::drivers
