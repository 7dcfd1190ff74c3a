// toml++'s implementation, compiled once into tnv_toml_impl when the
// programs carry their libraries (TNV_STATIC_TOOLS, cmake/tnv_dependencies.cmake):
// Debian ships toml++ as headers and a shared library, no static archive.
#define TOML_IMPLEMENTATION 1
#include <toml++/toml.h>
