// The translation unit that builds the host tools' shared precompiled
// header (tnv_tools_pch in cmake/tnv_precompiled_headers.cmake); it has no
// code of its own.
