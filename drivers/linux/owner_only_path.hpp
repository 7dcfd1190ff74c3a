#pragma once
// The board's own files and sockets: a directory the daemon puts its CAN
// socket or its parameters in must not be one another user can write
// (they could replace the socket or the image under it). Checked before
// anything is created; what is created is owner-only.
#include <string>

namespace tnv::drivers {

// Why `dir` may not hold the daemon's files, or "": it is writable by
// group or others without the sticky bit (/tmp, with it, is fine: nobody
// can remove or rename another user's entry there), or it belongs to a
// user other than this one or root. A directory that does not exist yet
// is judged by its nearest existing parent (it will be created 0700).
std::string unsafe_directory(const std::string& dir);

// The directory `path` is in ("." for a bare name).
std::string parent_directory(const std::string& path);

}  // namespace tnv::drivers
