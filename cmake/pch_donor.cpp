// The translation unit that builds a precompiled header shared by several
// targets (cmake/tnv_precompiled_headers.cmake); it has no code of its own.
